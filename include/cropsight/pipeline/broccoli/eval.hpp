#pragma once
// Evaluation of the broccoli pipeline against ground truth, per frame (Evaluator: the detector's
// Table I confusion and Table II AP of Montes et al.) and per pass (TrackingEvaluator in
// tracking_eval.hpp: sizes, temporal AP, the field map). Ground truth is joined to the detector's
// clusters by the rules of TruthRules (truth.hpp); the pipeline itself never reads labels.
#include <cstdint>
#include <vector>

#include "cropsight/core/timer.hpp"
#include "cropsight/eval/binary_metrics.hpp"
#include "cropsight/eval/detection_ap.hpp"
#include "cropsight/pipeline/broccoli/pipeline.hpp"
#include "cropsight/pipeline/broccoli/truth.hpp"

namespace cropsight::pipeline::broccoli {

struct Figures {
  long frames = 0;
  long clusters = 0;
  std::int64_t truth_heads = 0;       ///< ground-truth heads counted by AP
  std::int64_t detections = 0;        ///< clusters classified as heads
  eval::BinaryConfusion confusion;    ///< per cluster (Table I)
  double ap50 = 0.0, map50_95 = 0.0;  ///< Table II, every labelled head counts
  /// Same with heads cut by the image border ignored (COCO-style ignore: they neither count nor
  /// turn a detection of them into a false positive).
  double ap50_in_view = 0.0, map50_95_in_view = 0.0;
  std::int64_t truth_heads_in_view = 0;
  /// Same with heads of fewer than detection.visible_truth_points visible points ignored.
  double ap50_visible = 0.0, map50_95_visible = 0.0;
  std::int64_t truth_heads_visible = 0;
  /// ap50 and ap50_visible with the truth of every pixel the sensor measured, whatever the depth
  /// window (truth_instances_any_depth): a head outside the window is a miss here, not uncounted.
  double ap50_any_depth = 0.0, ap50_visible_any_depth = 0.0;
  std::int64_t truth_heads_any_depth = 0, truth_heads_visible_any_depth = 0;
  double pipeline_ms = 0.0;  ///< total wall-clock time in Detector::process (I/O excluded)
  double fps() const { return pipeline_ms > 0 ? 1000.0 * double(frames) / pipeline_ms : 0.0; }
  double ms_per_frame() const { return frames ? pipeline_ms / double(frames) : 0.0; }
  std::vector<StageTimer::Stage> stages;  ///< per-stage totals
  std::vector<StageMs> stage_ms_per_frame() const { return per_frame_ms(stages, frames); }
};

/// Runs a pipeline over frames with labels and accumulates Table I and II metrics of its detector.
/// AP ranks every cluster by its score (all candidates, not only those above the threshold).
class Evaluator {
 public:
  explicit Evaluator(Pipeline& pipeline);
  /// pipeline.process(frame), then the frame's figures (the result stays in pipeline.last() for a
  /// TrackingEvaluator). Throws Error("frame N", ...) when the frame has no label image.
  void add_frame(const RgbdFrame& frame);
  Figures figures() const;

 private:
  Pipeline& pipeline_;
  Figures r_;
  eval::DetectionApAccumulator ap_, ap_view_, ap_visible_, ap_any_, ap_any_visible_;
  std::vector<bool> cut_, small_;
  std::vector<TruthInstance> truth_;
  std::vector<std::vector<int>> truth_sets_;
};

}  // namespace cropsight::pipeline::broccoli
