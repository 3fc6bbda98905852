#include "cropsight/pipeline/broccoli/steps/clustering_step.hpp"

#include <utility>

#include "cropsight/geometry/depth_filter.hpp"  // valid_indices
#include "cropsight/geometry/statistical_outlier.hpp"

namespace cropsight::pipeline::broccoli::steps {

ClusteringStep::ClusteringStep(Variant variant, segmentation::OrgConfig org, segmentation::EuclideanClusterConfig fec,
                               OutlierStageConfig outliers)
    : variant_(variant), org_(org), fec_(fec), outliers_(outliers) {}

std::vector<Segment> ClusteringStep::run(const OrganizedCloud& cloud, const std::vector<std::uint8_t>& edges,
                                         const segmentation::OesConfig& oes, std::vector<int>& owners,
                                         StageTimer& timer) {
  if (variant_ == Variant::fec) {
    owners.clear();
    return fec_clusters(cloud, timer);
  }
  auto t = timer.scope("clustering");
  std::vector<Segment> segments =
      variant_ == Variant::oes ? oes_passes(cloud, edges, oes) : segmentation::segment_org(cloud, org_, flood_);
  owners.swap(flood_.labels);  // the frame's owner image; the step reuses the old one's buffer
  return segments;
}

std::vector<Segment> ClusteringStep::oes_passes(const OrganizedCloud& cloud, const std::vector<std::uint8_t>& edges,
                                                const segmentation::OesConfig& oes) {
  std::vector<Segment> segments = segmentation::segment_oes(cloud, edges, oes, flood_);
  if (oes.debris_tolerance > 0.0f) debris_pass(cloud, edges, oes, segments);
  return segments;
}

void ClusteringStep::debris_pass(const OrganizedCloud& cloud, const std::vector<std::uint8_t>& edges,
                                 const segmentation::OesConfig& oes, std::vector<Segment>& segments) {
  // The pixels of kept segments become a barrier (a bit no edge label uses) for the second pass.
  constexpr std::uint8_t kKept = 0x80;
  const std::size_t n = edges.size();
  debris_edges_.resize(n);
  kept_labels_.assign(flood_.labels.begin(), flood_.labels.end());
  for (std::size_t i = 0; i < n; ++i) debris_edges_[i] = std::uint8_t(edges[i] | (kept_labels_[i] >= 0 ? kKept : 0));
  segmentation::OesConfig second = oes;
  second.distance_tolerance = oes.debris_tolerance;
  second.barrier_labels = oes.barrier_labels | kKept;
  std::vector<Segment> more = segmentation::segment_oes(cloud, debris_edges_, second, flood_);
  // One label image for both passes (the lazy normals select by it): second-pass ids follow the first's.
  const int offset = int(segments.size());
  for (std::size_t i = 0; i < n; ++i)
    if (flood_.labels[i] >= 0) kept_labels_[i] = flood_.labels[i] + offset;
  flood_.labels.swap(kept_labels_);
  for (Segment& s : more) segments.push_back(std::move(s));
}

std::vector<Segment> ClusteringStep::fec_clusters(const OrganizedCloud& cloud, StageTimer& timer) {
  valid_ = geometry::valid_indices(cloud);
  if (outliers_.enabled) {
    auto t = timer.scope("outliers");
    valid_ = geometry::remove_statistical_outliers(cloud, valid_, outliers_.sor);
  }
  auto t = timer.scope("clustering");
  return segmentation::euclidean_clusters(cloud, valid_, fec_);
}

}  // namespace cropsight::pipeline::broccoli::steps
