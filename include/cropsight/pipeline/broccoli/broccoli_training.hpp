#pragma once
// Training and evaluation of broccoli head detectors over frames with ground truth. Frame
// sources are the caller's (a SequenceReader in the CLI, simulated frames in tests), so these
// classes take one RgbdFrame at a time. Ground truth is joined to the detector's clusters here,
// by the rules of BroccoliTruthRules (the detector never reads labels).
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "cropsight/core/timer.hpp"
#include "cropsight/eval/binary_metrics.hpp"
#include "cropsight/eval/detection_ap.hpp"
#include "cropsight/learning/dataset.hpp"
#include "cropsight/learning/model.hpp"
#include "cropsight/pipeline/broccoli/broccoli_detector.hpp"
#include "cropsight/pipeline/broccoli/broccoli_pipeline.hpp"
#include "cropsight/pipeline/broccoli/broccoli_truth.hpp"

namespace cropsight::pipeline {

/// Every cluster of every added frame as a (features, head?) sample, labelled by the cluster
/// rule of broccoli_truth.hpp.
class BroccoliDatasetBuilder {
 public:
  BroccoliDatasetBuilder(const BroccoliDetectorConfig& cfg, const BroccoliTruthRules& truth);
  /// Throws Error("frame N", ...) when the frame has no label image.
  void add_frame(const RgbdFrame& frame);
  const learning::Dataset& dataset() const { return data_; }
  long frames() const { return frames_; }
  /// The detector that builds the samples: the config without the detection-only stages
  /// (denoising unless denoise.in_training, the head CNN); its timer holds the stage times.
  const BroccoliDetector& detector() const { return detector_; }

 private:
  BroccoliDetector detector_;
  BroccoliTruthRules truth_;
  learning::Dataset data_;
  long frames_ = 0;
};

/// The training configuration as a flat map (what a model file records): the detector's keys and
/// the truth rules (detection.*) the training labels were made with; never sizing.* / tracking.*.
ConfigMap config_map(const BroccoliDetectorConfig& cfg, const BroccoliTruthRules& truth);

/// Trains cfg.classifier on `data` and fills the model's metadata (task, pipeline, features,
/// config, provenance).
learning::Model train_broccoli_model(const learning::Dataset& data, const BroccoliDetectorConfig& cfg,
                                     const BroccoliTruthRules& truth, std::map<std::string, std::string> provenance);

struct BroccoliEvalResult {
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
  double pipeline_ms = 0.0;  ///< total wall-clock time in BroccoliDetector::process (I/O excluded)
  double fps() const { return pipeline_ms > 0 ? 1000.0 * double(frames) / pipeline_ms : 0.0; }
  std::vector<StageTimer::Stage> stages;  ///< per-stage totals
};

/// Runs a pipeline over frames with labels and accumulates Table I and II metrics of its detector.
/// AP ranks every cluster by its score (all candidates, not only those above the threshold).
class BroccoliEvaluator {
 public:
  explicit BroccoliEvaluator(BroccoliPipeline& pipeline);
  /// pipeline.process(frame), then the frame's figures (the result stays in pipeline.last() for a
  /// BroccoliTrackingEvaluator). Throws Error("frame N", ...) when the frame has no label image.
  void add_frame(const RgbdFrame& frame);
  BroccoliEvalResult result() const;

 private:
  BroccoliPipeline& pipeline_;
  BroccoliEvalResult r_;
  eval::DetectionApAccumulator ap_, ap_view_, ap_visible_, ap_any_, ap_any_visible_;
  std::vector<bool> cut_, small_;
  std::vector<TruthInstance> truth_;
  std::vector<std::vector<int>> truth_sets_;
};

}  // namespace cropsight::pipeline
