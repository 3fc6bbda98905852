#pragma once
// The broccoli pipeline's one configuration: every key of a broccoli preset (configs/broccoli-*.yaml,
// --set key=value). The detector's keys sit at the top level (detector_config.hpp: depth.*, oes.*,
// classifier.*, ...), the ground-truth rules under detection.*, sizing under sizing.* and the
// temporal filter under tracking.*. A model file records the detector and truth keys it was trained
// with; config_for_model lays a preset and --set values over them.
#include <filesystem>
#include <memory>
#include <string>

#include "cropsight/core/config.hpp"
#include "cropsight/learning/model.hpp"
#include "cropsight/pipeline/broccoli/detector_config.hpp"
#include "cropsight/tracking/head_mapper.hpp"

namespace cropsight::pipeline::broccoli {

/// Every key of a broccoli preset: the detector's at the top level (pipeline, features, depth.*,
/// oes.*, …), the truth rules under detection.*, sizing.* and tracking.*.
struct Config {
  DetectorConfig detector;
  TruthRules truth;  ///< training labels and evaluation only
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
std::shared_ptr<const learning::Model> load_model(const std::filesystem::path& path);

/// The config a pipeline runs with: defaults ← what `model` records (its training config) ←
/// `overrides` (a preset and --set values). Throws Error naming `where` (the model) or
/// `overrides_where` (the preset) on an unknown key or a bad value.
Config config_for_model(const learning::Model& model, const ConfigMap& overrides, const std::string& where,
                        const std::string& overrides_where = "--config/--set");

}  // namespace cropsight::pipeline::broccoli
