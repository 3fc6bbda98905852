#pragma once
// The potato paper's detection metric: Pascal VOC all-point AP as computed by pascalvoc.py of
// rafaelpadilla/Object-Detection-Metrics (the authors' evaluation), for one class.
//
// Boxes are pixel corners (x1, y1, x2, y2) with the corners inclusive: area =
// (x2 − x1 + 1)·(y2 − y1 + 1), intersection likewise, and boxes that do not overlap (x1 of one
// beyond x2 of the other, likewise y) have IoU 0 — so boxes that touch share one pixel row.
//
// Matching, exactly as pascalvoc.py: the detections of all images are ranked by decreasing score
// (stable: ties keep image order, then file order). Each detection takes the truth of its image
// with the highest IoU over *all* that image's truths (the first on ties); it is a true positive
// when that IoU ≥ the threshold and that truth is not matched yet (the truth is then matched),
// otherwise a false positive — a detection whose best truth is already taken is not moved on to
// its second best. (This differs from COCO-style matching, which takes the best unmatched truth;
// the paper's figures depend on it only where two truths overlap.) "difficult" flags are not
// used (pascalvoc.py ignores them).
//
// AP: precision/recall after each ranked detection, recall relative to all truths;
// AP = Σ (r_i − r_{i−1})·max_{j ≥ i} p_j (all-point interpolation). NaN without any truth.
#include <cstdint>
#include <vector>

namespace cropsight::eval {

/// A box in pixels with inclusive corners; `score` is used for detections only.
struct VocBox {
  double x1 = 0, y1 = 0, x2 = 0, y2 = 0;
  double score = 1.0;
};

/// One image's ground truth and detections (of the class being evaluated).
struct VocImage {
  std::vector<VocBox> truth;
  std::vector<VocBox> detections;
};

/// IoU with inclusive pixel areas (see above); 0 for boxes that do not overlap.
double voc_iou(const VocBox& a, const VocBox& b);

/// All-point AP at `iou_threshold` (a detection matches when IoU ≥ threshold).
double voc_ap(const std::vector<VocImage>& images, double iou_threshold);

struct VocApSummary {
  double ap50 = 0, ap75 = 0;
  double map50_95 = 0;  ///< mean AP over thresholds 0.50, 0.55, …, 0.95
  std::int64_t images = 0, truths = 0, detections = 0;
};
VocApSummary voc_ap_summary(const std::vector<VocImage>& images);

}  // namespace cropsight::eval
