#pragma once
// Weighted boxes fusion (Solovyev, Wang, Gabruseva 2019, "Weighted boxes fusion: ensembling boxes
// from different object detection models"): the boxes of several detectors on one image become one
// list. All boxes, by decreasing score, join the first cluster of their class whose fused box they
// overlap with IoU >= `iou_threshold` and that holds no box of their own detector yet, else start
// one. A cluster's box is the score-weighted mean of its boxes' corners; its score is the sum of its
// scores divided by the number of detectors, so a box only one detector saw keeps 1/N of its score
// and boxes that all detectors agree on rank first. Boxes are image pixels (Detection2D). Used by the
// potato pipeline's `fusion` backend (docs/pipelines/potatoes.md) to join the classical detector
// and the trained CNN.
#include <memory>
#include <string>
#include <vector>

#include "cropsight/core/config.hpp"
#include "cropsight/core/detection2d.hpp"

namespace cropsight {

struct BoxFusionConfig {
  double iou_threshold = 0.55;  ///< the paper's default (its skip threshold is 0: every box joins)

  template <class V>
  void visit(V& v) {
    v("iou_threshold", iou_threshold,
      "a box joins a cluster whose fused box it overlaps with IoU >= this (Solovyev et al. 2019: 0.55)",
      Range::within(0, 1));
  }
};

/// The fused boxes of `per_detector` (one list per detector, any order), highest score first.
/// Scores are divided by per_detector.size(); boxes of different classes never fuse.
std::vector<Detection2D> weighted_boxes_fusion(const std::vector<std::vector<Detection2D>>& per_detector,
                                               const BoxFusionConfig& cfg = {});

/// A Detector2D that runs several detectors on the same input and fuses their boxes. The
/// detectors must name the same classes in the same order (checked at construction). Not
/// thread-safe, as its detectors.
class FusedDetector final : public Detector2D {
 public:
  FusedDetector(std::vector<std::unique_ptr<Detector2D>> detectors, BoxFusionConfig cfg = {});
  std::vector<Detection2D> detect(const DetectorInput& in) override;
  std::vector<std::string> class_names() const override;

 private:
  std::vector<std::unique_ptr<Detector2D>> detectors_;
  BoxFusionConfig cfg_;
};

}  // namespace cropsight
