#pragma once
// Training of broccoli head detectors over frames with ground truth (evaluation: eval.hpp). Frame
// sources are the caller's (a SequenceReader in the CLI, simulated frames in tests), so these
// classes take one RgbdFrame at a time. Ground truth is joined to the detector's clusters here,
// by the rules of TruthRules (the detector never reads labels).
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "cropsight/core/timer.hpp"
#include "cropsight/learning/dataset.hpp"
#include "cropsight/learning/model.hpp"
#include "cropsight/pipeline/broccoli/detector.hpp"
#include "cropsight/pipeline/broccoli/truth.hpp"

namespace cropsight::pipeline::broccoli {

/// Every cluster of every added frame as a (features, head?) sample, labelled by the cluster
/// rule of broccoli/truth.hpp.
class DatasetBuilder {
 public:
  DatasetBuilder(const DetectorConfig& cfg, const TruthRules& truth);
  /// Throws Error("frame N", ...) when the frame has no label image.
  void add_frame(const RgbdFrame& frame);
  const learning::Dataset& dataset() const { return data_; }
  long frames() const { return frames_; }
  /// The detector that builds the samples: the config without the detection-only stages
  /// (denoising unless denoise.in_training, the head CNN); its timer holds the stage times.
  const Detector& detector() const { return detector_; }

 private:
  Detector detector_;
  TruthRules truth_;
  learning::Dataset data_;
  long frames_ = 0;
};

/// The training configuration as a flat map (what a model file records): the detector's keys and
/// the truth rules (detection.*) the training labels were made with; never sizing.* / tracking.*.
ConfigMap config_map(const DetectorConfig& cfg, const TruthRules& truth);

/// Trains cfg.classifier on `data` and fills the model's metadata (task, pipeline, features,
/// config, provenance).
learning::Model train_model(const learning::Dataset& data, const DetectorConfig& cfg, const TruthRules& truth,
                            std::map<std::string, std::string> provenance);

}  // namespace cropsight::pipeline::broccoli
