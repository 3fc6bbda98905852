#pragma once
// Shared by the seedling and stereo sub-commands (detect / eval / simulate seedling, stereo,
// eval stereo): configuration loading and the JSON forms of a detection and an evaluation.
#include <nlohmann/json.hpp>
#include <string>

#include "cli_common.hpp"
#include "cropsight/core/config.hpp"
#include "cropsight/io/config_yaml.hpp"
#include "cropsight/pipeline/seedling/eval.hpp"
#include "cropsight/pipeline/seedling/pipeline.hpp"

namespace cropsight::cli {

/// Applies the preset (--config, else `default_preset` when non-empty) and then the --set values
/// to `cfg`, calling `validate(cfg, where)` after each step. Keeping the two sources apart means
/// an error names where the bad value came from (the preset file or "--set") and, through
/// `validate`, the key, instead of blaming whichever input image the library reads first.
template <class Config, class Validate>
void apply_checked_config(Config& cfg, const CommonOptions& o, const std::string& default_preset, Validate&& validate) {
  const std::string preset = o.config.empty() ? default_preset : o.config;
  if (!preset.empty()) {
    const std::string where = o.config.empty() ? "configs/" + default_preset + ".yaml" : o.config;
    apply_config(cfg, io::load_config_map(io::find_preset(preset)), where);
    validate(cfg, where);
  }
  const ConfigMap sets = io::load_preset_with_overrides("", o.sets);
  if (sets.empty()) return;
  apply_config(cfg, sets, "--set");
  validate(cfg, "--set");
}

/// The seedling pipeline of the preset (default configs/seedling.yaml) with the --set overrides,
/// validated (pipeline::seedling::Config::validate); errors name the preset file or "--set" and the key.
pipeline::seedling::Pipeline seedling_pipeline(const CommonOptions& o);
/// found, envelope, plane, point counts, timings in ms per stage.
nlohmann::json seedling_json(const pipeline::seedling::FrameResult& d);
/// The figures of an evaluation, per pair and averaged (the cv::ml::EM keys only when compared).
nlohmann::json seedling_evaluation_json(const pipeline::seedling::Figures& e);

}  // namespace cropsight::cli
