#include "cropsight/pipeline/broccoli/steps/clustering_step.hpp"

#include <utility>

#include "core/cpu_dispatch.hpp"

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

namespace {
// The pixels of kept segments become a barrier (a bit no edge label uses) for the second pass.
constexpr std::uint8_t kKept = 0x80;

// barrier[i] = edges[i] plus kKept where the first pass kept pixel i (labels[i] >= 0). One
// branch-free pass that the compiler vectorises (-O3, AVX2 / AVX-512 clones).
CROPSIGHT_AVX2_CLONES void mark_kept(std::size_t n, const std::uint8_t* __restrict edges, const int* __restrict labels,
                                     std::uint8_t* __restrict barrier) {
  for (std::size_t i = 0; i < n; ++i) barrier[i] = std::uint8_t(edges[i] | (labels[i] >= 0 ? kKept : 0));
}

// labels[i] = second[i] + offset where the second pass kept pixel i (second[i] >= 0), else as it
// was: one label image for both passes, the second pass's ids after the first's. Vectorised.
CROPSIGHT_AVX2_CLONES void merge_labels(std::size_t n, const int* __restrict second, int offset,
                                        int* __restrict labels) {
  for (std::size_t i = 0; i < n; ++i) labels[i] = second[i] >= 0 ? second[i] + offset : labels[i];
}
}  // namespace

void ClusteringStep::debris_pass(const OrganizedCloud& cloud, const std::vector<std::uint8_t>& edges,
                                 const segmentation::OesConfig& oes, std::vector<Segment>& segments) {
  const std::size_t n = edges.size();
  debris_edges_.resize(n);
  // The first pass's labels move aside (no copy); the second pass fills the workspace's anew.
  kept_labels_.swap(flood_.labels);
  mark_kept(n, edges.data(), kept_labels_.data(), debris_edges_.data());
  segmentation::OesConfig second = oes;
  second.distance_tolerance = oes.debris_tolerance;
  second.barrier_labels = oes.barrier_labels | kKept;
  std::vector<Segment> more = segmentation::segment_oes(cloud, debris_edges_, second, flood_);
  // One label image for both passes (the lazy normals select by it): second-pass ids follow the first's.
  merge_labels(n, flood_.labels.data(), int(segments.size()), kept_labels_.data());
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
