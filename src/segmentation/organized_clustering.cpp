#include "cropsight/segmentation/organized_clustering.hpp"

#include <cmath>

#include "cropsight/core/error.hpp"

namespace cropsight::segmentation {

namespace {
void check_sizes(const char* where, float tolerance, int min_size, int max_size) {
  if (!(tolerance > 0.0f)) throw Error(where, "distance_tolerance must be > 0");
  if (min_size < 1 || max_size < min_size) throw Error(where, "size range must satisfy 1 <= min_size <= max_size");
}
}  // namespace

std::vector<Segment> segment_oes(const OrganizedCloud& cloud, const std::vector<std::uint8_t>& edges,
                                 const OesConfig& cfg, FloodFillWorkspace& ws) {
  check_sizes("oes", cfg.distance_tolerance, cfg.min_size, cfg.max_size);
  if (edges.size() != cloud.size()) throw Error("oes", "edge label image size differs from the cloud size");
  if (cfg.barrier_labels < 0 || cfg.barrier_labels > 255)
    throw Error("oes", "barrier_labels must be a bit mask in 0..255");
  const OesPredicate pred{cloud.x.data(),
                          cloud.y.data(),
                          cloud.z.data(),
                          edges.data(),
                          std::uint8_t(cfg.barrier_labels),
                          cfg.distance_tolerance * cfg.distance_tolerance};
  return flood_fill_segments(cloud, pred, cfg.min_size, cfg.max_size, ws);
}

std::vector<Segment> segment_org(const OrganizedCloud& cloud, const OrgConfig& cfg, FloodFillWorkspace& ws) {
  check_sizes("org", cfg.distance_tolerance, cfg.min_size, cfg.max_size);
  if (!cloud.has_normals() || cloud.nx.size() != cloud.size() || cloud.curvature.size() != cloud.size())
    throw Error("org", "the cloud has no normals (estimate them first)");
  if (!(cfg.angle_threshold >= 0.0f && cfg.angle_threshold <= 3.14159265f))
    throw Error("org", "angle_threshold must be in [0, pi] radians");
  const OrgPredicate pred{cloud.x.data(),          cloud.y.data(),
                          cloud.z.data(),          cloud.nx.data(),
                          cloud.ny.data(),         cloud.nz.data(),
                          cloud.curvature.data(),  std::cos(cfg.angle_threshold),
                          cfg.curvature_threshold, cfg.distance_tolerance * cfg.distance_tolerance};
  return flood_fill_segments(cloud, pred, cfg.min_size, cfg.max_size, ws);
}

}  // namespace cropsight::segmentation
