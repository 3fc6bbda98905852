#pragma once
// Evaluation of a grape segmentation model on labelled clouds it was not trained on: the
// paper's OAcc / mAcc / mIoU, per-class accuracy and IoU (labels 0-5), and the time per cloud.
#include <functional>
#include <string>
#include <vector>

#include "cropsight/core/cloud.hpp"
#include "cropsight/eval/segmentation_metrics.hpp"
#include "cropsight/pipeline/grape_model.hpp"

namespace cropsight::pipeline {

struct GrapeEvaluation {
  eval::ConfusionMatrix confusion{6};
  std::size_t clouds = 0;
  std::size_t points = 0;
  double seconds = 0;  ///< wall time of segment() summed over clouds (features + inference)

  double ms_per_cloud() const { return clouds ? 1000.0 * seconds / double(clouds) : 0.0; }
  void merge(const GrapeEvaluation& o);
  /// {"clouds", "points", "oacc", "macc", "miou", "per_class": [{"label", "points", "accuracy",
  /// "iou"}], "ms_per_cloud"} as JSON text; undefined values are null.
  std::string json() const;
  /// Human-readable summary (several lines).
  std::string text() const;
};

/// Segments each cloud with `model` (timed) and accumulates the confusion matrix against the
/// clouds' labels. Labels >= num_classes throw Error.
GrapeEvaluation evaluate_grape(const GrapeModel& model, const std::vector<Cloud>& clouds, int num_classes = 6);

}  // namespace cropsight::pipeline
