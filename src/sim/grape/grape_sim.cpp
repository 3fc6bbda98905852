// simulate_grape_cloud: the ray-cast region of interest turned into the dataset's kind of cloud —
// sensor effects (mixed depth along silhouettes, depth and colour noise), KNN-PCA normals as the
// grape pipeline computes them, the dataset's frame and the unit-sphere normalisation.
#include <algorithm>
#include <cmath>

#include "cropsight/core/error.hpp"
#include "cropsight/geometry/knn_normals.hpp"
#include "grape_scene.hpp"

namespace cropsight::sim {

namespace {

using detail::GrapeHit;
using detail::PixelRect;

// The camera frame turned 180 degrees about x: the frame of the shared clouds (header).
const Eigen::Matrix3f kToDataset = Eigen::Vector3f(1, -1, -1).asDiagonal();

// Mixed pixels: a pixel on the far side of a silhouette, within `band` pixels of a surface nearer
// by more than `jump`, takes a depth between the two, as a depth sensor's flying pixels do, and
// becomes label 5. A hole counts as lying at the backdrop's depth.
void mix_silhouettes(std::vector<GrapeHit>& hits, const PixelRect& roi, const GrapeSimConfig& cfg, double backdrop_z,
                     Rng& rng) {
  const auto at = [&](int i, int j) -> const GrapeHit& {
    return hits[std::size_t(j) * std::size_t(roi.width) + std::size_t(i)];
  };
  const auto depth_of = [&](const GrapeHit& h) { return h.depth > 0 ? double(h.depth) : backdrop_z; };
  std::vector<float> nearest(hits.size(), 0.f);
  const int b = cfg.edge_band_px;
  for (int j = 0; j < roi.height; ++j)
    for (int i = 0; i < roi.width; ++i) {
      double near = depth_of(at(i, j));
      for (int y = std::max(0, j - b); y <= std::min(roi.height - 1, j + b); ++y)
        for (int x = std::max(0, i - b); x <= std::min(roi.width - 1, i + b); ++x)
          if (at(x, y).depth > 0) near = std::min(near, double(at(x, y).depth));
      nearest[std::size_t(j) * std::size_t(roi.width) + std::size_t(i)] = float(near);
    }
  for (std::size_t k = 0; k < hits.size(); ++k) {
    GrapeHit& h = hits[k];
    const double far = depth_of(h);
    if (far - nearest[k] <= cfg.edge_jump || !rng.bernoulli(0.8)) continue;
    h.depth = float(nearest[k] + rng.uniform(0.1, 0.9) * (far - nearest[k]));
    h.label = kGrapeNoise;
    h.color = 0.6f * h.color + Eigen::Vector3f::Constant(0.2f);
    const int i = int(k % std::size_t(roi.width)), j = int(k / std::size_t(roi.width));
    h.position =
        Eigen::Vector3f(float((roi.u0 + i + 0.5) / cfg.focal_px), float((roi.v0 + j + 0.5) / cfg.focal_px), 1.f) *
        h.depth;
  }
}

// Pixels to points in the camera frame: deprojected with depth noise, colour noise; pixels
// without a return at the camera centre. Fills the truth's label counts and cut point.
Cloud deproject(const std::vector<GrapeHit>& hits, const GrapeSimConfig& cfg, Rng& rng, GrapeSimTruth& truth) {
  Cloud cloud;
  Eigen::Vector3f peduncle_sum = Eigen::Vector3f::Zero();
  for (std::size_t k = 0; k < hits.size(); ++k) {
    const GrapeHit& h = hits[k];
    Eigen::Vector3f p = Eigen::Vector3f::Zero();
    if (h.depth > 0) {
      const double z = h.depth + rng.normal(0.0, cfg.depth_noise * double(h.depth) * double(h.depth));
      p = h.position * float(z / h.depth);
    }
    Eigen::Vector3f c = h.color;
    for (int ch = 0; ch < 3; ++ch) c[ch] = std::clamp(float(c[ch] + rng.normal(0.0, cfg.color_noise)), 0.f, 1.f);
    cloud.points.push_back(p);
    cloud.colors.push_back(c);
    cloud.labels.push_back(h.label);
    ++truth.label_counts[std::size_t(h.label)];
    if (h.label == kGrapePeduncle) peduncle_sum += h.position;
  }
  truth.peduncle_points = int(truth.label_counts[kGrapePeduncle]);
  if (truth.peduncle_points > 0) truth.cut_point_m = peduncle_sum / float(truth.peduncle_points);
  return cloud;
}

// KNN-PCA normals (k = 30, toward the camera), as grape_roi_clouds computes them; the points
// without a return share one position, so they get the normal toward the camera.
void add_normals(Cloud& cloud) {
  std::vector<Eigen::Vector3f> seen;
  std::vector<std::size_t> index;
  for (std::size_t k = 0; k < cloud.size(); ++k)
    if (cloud.labels[k] != kGrapeNoReturn) {
      seen.push_back(cloud.points[k]);
      index.push_back(k);
    }
  cloud.normals.assign(cloud.size(), Eigen::Vector3f(0, 0, -1));
  if (seen.size() < 3) return;
  const std::vector<Eigen::Vector3f> normals = geometry::knn_normals(seen);
  for (std::size_t k = 0; k < seen.size(); ++k) cloud.normals[index[k]] = normals[k];
}

}  // namespace

void GrapeSimConfig::validate(const std::string& where) const {
  check_config(*this, where);
  const auto order = [&](double lo, double hi, const char* lo_key, const char* hi_key) {
    if (lo > hi) throw Error(where, std::string("'") + lo_key + "' must not exceed '" + hi_key + "'");
  };
  order(distance_min, distance_max, "distance_min", "distance_max");
  order(backdrop_min, backdrop_max, "backdrop_min", "backdrop_max");
  order(bunch_length_min, bunch_length_max, "bunch_length_min", "bunch_length_max");
  order(bunch_radius_min, bunch_radius_max, "bunch_radius_min", "bunch_radius_max");
  order(berries_min, berries_max, "berries_min", "berries_max");
  order(berry_radius_min, berry_radius_max, "berry_radius_min", "berry_radius_max");
  order(peduncle_length_min, peduncle_length_max, "peduncle_length_min", "peduncle_length_max");
  order(leaves_min, leaves_max, "leaves_min", "leaves_max");
  order(leaf_size_min, leaf_size_max, "leaf_size_min", "leaf_size_max");
}

Eigen::Vector3f GrapeSimCloud::to_camera(const Eigen::Vector3f& p) const {
  return kToDataset.transpose() * (p * scale + centroid);
}

GrapeSimCloud simulate_grape_cloud(const GrapeSimConfig& cfg, std::uint64_t seed) {
  cfg.validate("grape simulator");
  const detail::GrapeScene scene = detail::build_grape_scene(cfg, seed);
  const PixelRect roi = detail::grape_roi(scene, cfg.focal_px);
  std::vector<GrapeHit> hits = detail::cast_grape_scene(scene, cfg.focal_px, roi);
  Rng rng(derive_seed(seed, {0x6e6f697365}));
  mix_silhouettes(hits, roi, cfg, scene.backdrop_z, rng);

  GrapeSimCloud sim;
  GrapeSimTruth& t = sim.truth;
  t.seed = seed;
  t.distance_m = scene.distance;
  t.berries = scene.berries;
  t.leaves = int(scene.leaves.size());
  t.peduncle_axis = scene.peduncle_axis.cast<float>();
  t.roi_width = roi.width;
  t.roi_height = roi.height;
  sim.cloud = deproject(hits, cfg, rng, t);
  add_normals(sim.cloud);
  for (std::size_t k = 0; k < sim.cloud.size(); ++k) {
    sim.cloud.points[k] = kToDataset * sim.cloud.points[k];
    sim.cloud.normals[k] = kToDataset * sim.cloud.normals[k];
  }
  std::tie(sim.centroid, sim.scale) = geometry::normalize_unit_sphere(sim.cloud.points);
  return sim;
}

}  // namespace cropsight::sim
