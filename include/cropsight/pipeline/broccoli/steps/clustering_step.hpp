#pragma once
// The clustering of [montes] §III on the broccoli detector's cloud (StageTimer "outliers",
// "clustering"):
//
//   OES: flood fill over the organised cloud, bounded by the edge labels; with
//        oes.debris_tolerance > 0 a second pass, with that looser tolerance, over the valid
//        pixels the first kept in no segment (kept pixels are a barrier to it)
//   ORG: flood fill on the normals' angle, grown from low-curvature points (needs normals)
//   FEC: [statistical outlier removal] + Euclidean clustering (k-d tree) of the valid points
//
// Segments hold pixel indices of the cloud (v * width + u) and their summaries (metres, camera
// frame). The flood fill's buffers are reused from frame to frame; the segments and FEC's index
// lists are what the segmentation functions return.
#include <cstdint>
#include <vector>

#include "cropsight/core/organized_cloud.hpp"
#include "cropsight/core/segment.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/pipeline/broccoli/detector_config.hpp"
#include "cropsight/segmentation/euclidean_clustering.hpp"
#include "cropsight/segmentation/organized_clustering.hpp"

namespace cropsight::pipeline::broccoli::steps {

class ClusteringStep {
 public:
  ClusteringStep(Variant variant, segmentation::OrgConfig org, segmentation::EuclideanClusterConfig fec,
                 OutlierStageConfig outliers);

  /// The segments of `cloud`: OES with `edges` (EdgesStep) and the frame's `oes` thresholds. The
  /// organised clusterings leave their label image in `owners` (per pixel: the segment's index
  /// or -1; the buffer is swapped with the step's, not copied); FEC leaves `owners` empty.
  std::vector<Segment> run(const OrganizedCloud& cloud, const std::vector<std::uint8_t>& edges,
                           const segmentation::OesConfig& oes, std::vector<int>& owners, StageTimer& timer);

 private:
  std::vector<Segment> oes_passes(const OrganizedCloud& cloud, const std::vector<std::uint8_t>& edges,
                                  const segmentation::OesConfig& oes);
  // The second OES pass; appends its segments, their ids following the first pass's in the labels.
  void debris_pass(const OrganizedCloud& cloud, const std::vector<std::uint8_t>& edges,
                   const segmentation::OesConfig& oes, std::vector<Segment>& segments);
  std::vector<Segment> fec_clusters(const OrganizedCloud& cloud, StageTimer& timer);

  Variant variant_;
  segmentation::OrgConfig org_;
  segmentation::EuclideanClusterConfig fec_;
  OutlierStageConfig outliers_;
  segmentation::OrganizedClusteringWorkspace flood_;
  std::vector<std::uint8_t> debris_edges_;  // the edges plus the first pass's kept pixels
  std::vector<int> kept_labels_;            // the first pass's labels, then both passes'
  std::vector<int> valid_;                  // FEC: the valid (then inlier) pixels
};

}  // namespace cropsight::pipeline::broccoli::steps
