#pragma once
// Pipeline: the broccoli systems of Montes et al. 2020 (detection) and Kusumam et al. 2017
// (sizing, temporal filter, field map) composed from ONE config, loaded from one preset
// (configs/broccoli-*.yaml) over the config a model file records:
//
//   per frame (process):
//     1. detect heads: organised cloud → normals → OES / ORG / FEC clusters → VFH … → classifier
//        (Detector, [montes] §III)
//     2. size each whole head: bounding box or convex hull + bias correction ([kusumam] §4.4)
//     3. temporal filter: associate the heads with the tracked ones, move the camera estimate
//        ([kusumam] §4.5); 2 and 3 are tracking::HeadMapper
//     4. predict the tracked heads this frame missed (extension, tracking.predict_missed)
//   per pass (finish): the field map.
//
// Without tracking (Config::track = false) only step 1 runs. No ground truth, no
// metric and no file writing happen here: Evaluator and TrackingEvaluator
// (eval.hpp, tracking_eval.hpp) join truth to the results, the CLI writes them.
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
#include "cropsight/core/timer.hpp"
#include "cropsight/learning/model.hpp"
#include "cropsight/pipeline/broccoli/config.hpp"
#include "cropsight/pipeline/broccoli/detector.hpp"
#include "cropsight/pipeline/broccoli/frame_result.hpp"
#include "cropsight/tracking/head_mapper.hpp"

namespace cropsight::pipeline::broccoli {

class Pipeline {
 public:
  /// Validates `cfg` and checks that `model` fits it (task, variant, features); throws Error(where, ...).
  Pipeline(const Config& cfg, std::shared_ptr<const learning::Model> model, const std::string& where = "model");

  /// Steps 1-4 on the next frame of the pass (frames in increasing order).
  FrameResult process(const RgbdFrame& frame);
  /// Ends the pass and returns the field map (empty without tracking). Call reset() for the next.
  const std::vector<tracking::TrackedHead>& finish();
  /// Starts a new pass: a fresh temporal filter; the detector and its buffers are kept.
  void reset();

  const Config& config() const { return cfg_; }
  const Detector& detector() const { return detector_; }
  Detector& detector() { return detector_; }
  /// The sizing + temporal filter state of the current pass (tracking only; throws otherwise).
  const tracking::HeadMapper& mapper() const;
  /// Whether this pass and the next keep every measured detection (HeadMapper::set_record_detections;
  /// default on: the evaluators and `detect broccoli --track` need them). Off for a live node.
  void set_record_detections(bool on);
  /// What the last process() returned (the evaluators read it after the pipeline ran).
  const FrameResult& last() const { return result_; }

 private:
  Config cfg_;
  Detector detector_;
  std::optional<tracking::HeadMapper> mapper_;
  FrameResult result_;
  std::vector<tracking::TrackedHead> no_map_;
  bool record_detections_ = true;
};

}  // namespace cropsight::pipeline::broccoli
