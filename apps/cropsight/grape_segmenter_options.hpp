#pragma once
// The options that `eval grape`, `segment grape` and `detect grape` share: a preset of the
// segmenter (--config, or the flag the command names, pipeline::grape::SegmenterConfig) and flags
// that override its keys one by one (--model → model, --sampled → sampled, --carry-k → carry_k,
// ...). Errors name the keys.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "cropsight/pipeline/grape/segmenter.hpp"
#include "cropsight/pipeline/pipeline_spec.hpp"

namespace cropsight::cli {

class GrapeSegmenterOptions {
 public:
  /// `default_preset`: the preset used when neither the preset flag nor --model is given ("" =
  /// none). `preset_flag`: the preset's option ("--config"; detect grape, whose --config is the
  /// pipeline's, says "--segmenter"). The preset flag also takes a model file (.pt, .json): that
  /// model with the default settings, as --model alone.
  void add_options(CLI::App* cmd, const std::string& default_preset = "", const std::string& preset_flag = "--config");
  /// The preset (if any) with the given flags applied; Error names the preset file or
  /// "command line" and the key. --threads stays the command's own option (set cfg.threads).
  pipeline::grape::SegmenterConfig config() const;
  /// The segmenter part of a pipeline spec (pipeline::grape::make_pipeline): its model is the
  /// preset flag's value (or the default preset when --model is not given either), the flags go
  /// to its sets as "segmenter.KEY=VALUE".
  void add_to_spec(pipeline::PipelineSpec& spec) const;
  /// Adds "votes" and, with an ensemble, "ensemble" and "ensemble_weight" to a JSON report.
  static void describe(const pipeline::grape::SegmenterConfig& cfg, nlohmann::json& j);

 private:
  /// The preset flag's value, or the default preset when neither it nor --model is given.
  std::string preset() const;

  std::string preset_, default_preset_, preset_flag_ = "--config";
  ConfigMap flags_;  // key → value text of the flags given
};

}  // namespace cropsight::cli
