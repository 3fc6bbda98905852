#pragma once
// BroccoliPipeline: the broccoli systems of Montes et al. 2020 (detection) and Kusumam et al. 2017
// (sizing, temporal filter, field map) composed from ONE config, loaded from one preset
// (configs/broccoli-*.yaml) over the config a model file records:
//
//   per frame (process):
//     1. detect heads: organised cloud → normals → OES / ORG / FEC clusters → VFH … → classifier
//        (BroccoliDetector, [montes] §III)
//     2. size each whole head: bounding box or convex hull + bias correction ([kusumam] §4.4)
//     3. temporal filter: associate the heads with the tracked ones, move the camera estimate
//        ([kusumam] §4.5); 2 and 3 are tracking::HeadMapper
//     4. predict the tracked heads this frame missed (extension, tracking.predict_missed)
//   per pass (finish): the field map.
//
// Without tracking (BroccoliPipelineConfig::track = false) only step 1 runs. No ground truth, no
// metric and no file writing happen here: BroccoliEvaluator and BroccoliTrackingEvaluator
// (broccoli_evaluation.hpp) join truth to the results, the CLI writes them.
//
// Not thread-safe: one pipeline per thread.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cropsight/core/config.hpp"
#include "cropsight/core/detection.hpp"
#include "cropsight/core/rgbd_frame.hpp"
#include "cropsight/learning/model.hpp"
#include "cropsight/pipeline/broccoli/broccoli_config.hpp"
#include "cropsight/pipeline/broccoli/broccoli_detector.hpp"
#include "cropsight/tracking/head_mapper.hpp"

namespace cropsight::pipeline {

/// Every key of a broccoli preset: the detector's at the top level (pipeline, features, depth.*,
/// oes.*, …), the truth rules under detection.*, sizing.* and tracking.*.
struct BroccoliPipelineConfig {
  BroccoliDetectorConfig detector;
  BroccoliTruthRules truth;  ///< training labels and evaluation only
  measure::HeadSizeConfig sizing;
  tracking::TemporalFilterConfig tracking;
  bool track = true;  ///< run steps 2-4 (the CLI's --track)

  template <class V>
  void visit(V& v) {
    detector.visit(v);
    v("detection", truth, "ground-truth rules (training and evaluation)");
    v("sizing", sizing, "head sizing ([kusumam] §4.4)");
    v("tracking", tracking, "temporal filter and field map ([kusumam] §4.5)");
    v("track", track, "bool; size and track heads over the frames of a pass (steps 2-4; detect/eval: --track)");
  }
  /// Throws Error(where, ...) when a value is out of range.
  void validate(const std::string& where) const;
  tracking::HeadMapperConfig mapping() const { return {sizing, tracking}; }
};

/// Loads a model file for the broccoli detector; throws Error(path, ...) when it is missing,
/// malformed or was trained for another task.
std::shared_ptr<const learning::Model> load_broccoli_model(const std::filesystem::path& path);

/// The config a pipeline runs with: defaults ← what `model` records (its training config) ←
/// `overrides` (a preset and --set values). Throws Error naming `where` (the model) or
/// `overrides_where` (the preset) on an unknown key or a bad value.
BroccoliPipelineConfig broccoli_config_for_model(const learning::Model& model, const ConfigMap& overrides,
                                                 const std::string& where,
                                                 const std::string& overrides_where = "--config/--set");

/// What process() found in one frame.
struct BroccoliFrameResult {
  int frame = 0;
  /// Heads, best score first. With tracking: size_m (0 = not measured: cut by the border) and
  /// track_id (the field map's head id) are set.
  std::vector<Detection> detections;
  std::vector<tracking::PredictedHead> predicted;  ///< tracking: heads of T this frame missed
  tracking::FrameAssociation association;          ///< tracking: the filter's update (camera estimate)
  double detect_ms = 0.0;                          ///< step 1, wall clock
  double track_ms = 0.0;                           ///< steps 2-4, wall clock
};

class BroccoliPipeline {
 public:
  /// Validates `cfg` and checks that `model` fits it (task, variant, features); throws Error(where, ...).
  BroccoliPipeline(const BroccoliPipelineConfig& cfg, std::shared_ptr<const learning::Model> model,
                   const std::string& where = "model");

  /// Steps 1-4 on the next frame of the pass (frames in increasing order). The result is valid
  /// until the next call.
  const BroccoliFrameResult& process(const RgbdFrame& frame);
  /// Ends the pass and returns the field map (empty without tracking). Call start_pass() for the next.
  const std::vector<tracking::TrackedHead>& finish();
  /// Starts a new pass: a fresh temporal filter; the detector and its buffers are kept.
  void start_pass();

  const BroccoliPipelineConfig& config() const { return cfg_; }
  const BroccoliDetector& detector() const { return detector_; }
  BroccoliDetector& detector() { return detector_; }
  /// The sizing + temporal filter state of the current pass (tracking only; throws otherwise).
  const tracking::HeadMapper& mapper() const;
  /// Whether this pass and the next keep every measured detection (HeadMapper::set_record_detections;
  /// default on: the evaluators and `detect broccoli --track` need them). Off for a live node.
  void set_record_detections(bool on);
  const BroccoliFrameResult& last() const { return result_; }

 private:
  BroccoliPipelineConfig cfg_;
  BroccoliDetector detector_;
  std::optional<tracking::HeadMapper> mapper_;
  BroccoliFrameResult result_;
  std::vector<tracking::TrackedHead> no_map_;
  bool record_detections_ = true;
};

}  // namespace cropsight::pipeline
