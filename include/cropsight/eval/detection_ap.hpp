#pragma once
// Detection average precision on point sets (Table II of Montes et al. 2020), where a detection
// and a ground-truth instance are both sets of point (pixel) indices of one frame.
//
// Matching at an IoU threshold t, frame by frame: detections are taken in decreasing score; each
// takes the not-yet-matched ground-truth instance with the highest point-set IoU, and is a true
// positive when that IoU ≥ t (the instance is then matched); otherwise it is a false positive
// (an instance can be matched once, so a duplicate detection of a found head is a false
// positive).
//
// AP: all detections of all frames ranked by score (ties: frame order, then order of input) give
// a precision/recall curve; AP is the all-point interpolated area under it (PASCAL VOC 2010+,
// also COCO's definition without its 101-point sampling):
//     AP = Σ_i (r_i − r_{i−1}) · max_{j ≥ i} p_j
// over the ranks i, r_0 = 0. Recall is relative to every ground-truth instance passed in, so an
// instance never detected lowers AP. mAP = mean of AP over t = 0.50, 0.55, …, 0.95 (COCO).
// With no ground-truth instance at all, AP is NaN.
//
// Ignored instances (COCO's "ignore" regions), e.g. heads cut by the image border: they do not
// count as ground truth; a detection that cannot be matched to a counted instance but reaches
// the threshold with an ignored one is dropped from the ranking (neither true nor false positive).
#include <cstdint>
#include <span>
#include <vector>

namespace cropsight::eval {

/// |A ∩ B| / |A ∪ B| of two index sets (each without duplicates; sorted or not). 0 when both
/// are empty.
double point_set_iou(std::span<const int> a, std::span<const int> b);

/// All-point interpolated AP of detections already marked correct/incorrect. `ranked` need not
/// be sorted: it is ordered by decreasing score (stable). num_truth = ground-truth instances.
struct RankedHit {
  float score = 0.0f;
  bool correct = false;
};
double average_precision(std::vector<RankedHit> ranked, std::int64_t num_truth);

/// One frame's ground-truth point sets and scored detections, kept whole (for precision-recall
/// curves, report::pr_curves); DetectionApAccumulator keeps only the overlaps.
struct ScoredFrame {
  std::vector<std::vector<int>> truth;
  struct Det {
    float score = 0.0f;
    std::vector<int> indices;
  };
  std::vector<Det> detections;
};

/// Accumulates frames, then answers AP at any threshold. Only the IoU of overlapping
/// (detection, truth) pairs is kept, not the point sets.
class DetectionApAccumulator {
 public:
  struct Scored {
    float score = 0.0f;
    std::span<const int> indices;
  };

  /// One frame: ground-truth instances and scored detections (point index sets of that frame).
  /// `ignored` (empty = none) flags instances that are not counted (see above).
  void add_frame(const std::vector<std::vector<int>>& truth, const std::vector<Scored>& detections,
                 const std::vector<bool>& ignored = {});

  std::int64_t num_truth() const { return num_truth_; }
  std::int64_t num_detections() const { return std::int64_t(dets_.size()); }
  /// AP at IoU threshold t (e.g. 0.5 → "AP50").
  double ap(double iou_threshold) const;
  /// Mean AP over 0.50:0.05:0.95.
  double map50_95() const;
  /// True positives at threshold t among detections with score > min_score (for reports).
  std::int64_t true_positives(double iou_threshold, float min_score) const;

 private:
  struct Det {
    int frame;
    float score;
    std::int64_t first_pair, num_pairs;  // into pairs_, sorted by IoU descending
  };
  struct Pair {
    int truth;  // truth instance index within the frame
    double iou;
  };
  std::vector<char> correct_at(double t) const;  // per detection: 1 TP, 0 FP, 2 ignored at t
  std::vector<Det> dets_;
  std::vector<Pair> pairs_;
  std::vector<std::int64_t> frame_first_det_;  // det index range per frame
  std::vector<int> frame_truths_;
  std::vector<std::vector<char>> frame_ignored_;  // per frame, per instance
  std::int64_t num_truth_ = 0;
};

}  // namespace cropsight::eval
