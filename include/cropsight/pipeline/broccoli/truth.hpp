#pragma once
// Ground truth for broccoli clusters, from a frame's label image (instance id per pixel, 0 =
// not a head).
//
// Cluster rule (used for training labels and for the cluster confusion matrix, Table I of
// Montes et al. 2020): a cluster is a head when at least `min_fraction` (default one half) of
// its points lie on ONE labelled head; its truth id is that head's id. A cluster spread over two
// heads with 40 % each is therefore not a head: it would not give a usable head position.
//
// Instance truth (for AP, Table II): the point set of head id h is every pixel labelled h that
// has a valid point after the depth filter — what the sensor actually saw of the head, the same
// kind of set a detection is.
#include <cstdint>
#include <span>
#include <vector>

#include "cropsight/core/organized_cloud.hpp"
#include "cropsight/core/rgbd_frame.hpp"

namespace cropsight::pipeline::broccoli {

struct ClusterTruth {
  int head_id = 0;        ///< majority head id, 0 when the cluster is not a head
  float fraction = 0.0f;  ///< share of the cluster's points on that head id
};

/// `labels`: width·height instance ids. Throws nothing; an empty `labels` gives "not a head".
ClusterTruth cluster_truth(std::span<const int> indices, std::span<const std::uint16_t> labels,
                           float min_fraction = 0.5f);

/// The cluster rule's verdict: cluster_truth(...).head_id != 0.
inline bool is_head(std::span<const int> indices, std::span<const std::uint16_t> labels, float min_fraction) {
  return cluster_truth(indices, labels, min_fraction).head_id != 0;
}

/// Throws Error("frame N", ...) when `frame` has no label image (training and evaluation need one).
void require_labels(const RgbdFrame& frame);

struct TruthInstance {
  int id = 0;
  std::vector<int> indices;    ///< ascending pixel indices of valid points labelled `id`
  bool cut_by_border = false;  ///< a pixel labelled `id` lies on the image border (head partly out of view)
};

/// Visible point sets of the labelled heads of `cloud` (which holds labels and depth-filtered
/// positions), ordered by id; heads with fewer than `min_points` visible points are left out.
/// Reuses `out`'s storage.
void truth_instances(const OrganizedCloud& cloud, int min_points, std::vector<TruthInstance>& out);

/// The same point sets over every pixel the sensor measured (`depth` > 0), whatever the detector's
/// depth window: the truth of the `*_any_depth` figures, where a head the window leaves out (a
/// camera higher than the window assumes) counts as a miss instead of not counting. `labels` and
/// `depth` hold width·height pixels (throws std::invalid_argument when their sizes differ).
void truth_instances_any_depth(std::span<const std::uint16_t> labels, std::span<const std::uint16_t> depth, int width,
                               int height, int min_points, std::vector<TruthInstance>& out);

}  // namespace cropsight::pipeline::broccoli
