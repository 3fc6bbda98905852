#include "grape_segmenter_options.hpp"

#include <filesystem>

#include <cstdio>

#include "cropsight/core/error.hpp"
#include "cropsight/io/config_yaml.hpp"

namespace cropsight::cli {

void GrapeSegmenterOptions::add_options(CLI::App* cmd, const std::string& default_preset,
                                        const std::string& preset_flag) {
  default_preset_ = default_preset;
  preset_flag_ = preset_flag;
  cmd->add_option(preset_flag, preset_,
                  "Segmenter preset (configs/<name>.yaml or a YAML file), e.g. grape-best: model, sampled, votes, "
                  "ensemble; or a model file (.pt, .json) with the default settings; the flags below override its "
                  "keys" +
                      (default_preset.empty() ? std::string() : " (default without --model: " + default_preset + ")"));
  // Each flag fills one key of pipeline::grape::SegmenterConfig; only the flags given override. Numbers
  // are typed, so that --help says INT / FLOAT and CLI11 refuses text before the config sees it.
  auto option = [&](const std::string& flag, const std::string& key, const std::string& help) {
    cmd->add_option_function<std::string>(
        flag, [this, key](const std::string& v) { flags_[key] = v; }, help);
  };
  auto integer = [&](const std::string& flag, const std::string& key, const std::string& help) {
    cmd->add_option_function<long>(
        flag, [this, key](long v) { flags_[key] = std::to_string(v); }, help);
  };
  auto number = [&](const std::string& flag, const std::string& key, const std::string& help) {
    cmd->add_option_function<double>(
        flag, [this, key](double v) { flags_[key] = detail::exact_number(v); }, help);
  };
  // A model file, or a shipped model's name (io::find_model), as --model everywhere.
  cmd->add_option_function<std::string>(
      "--model", [this](const std::string& v) { flags_["model"] = io::find_model(v).string(); },
      "Model: a shipped model's name (models/, e.g. grape-gbdt-fast) or a file (gbdt .json or network .pt)");
  cmd->add_flag_function(
      "--sampled", [this](std::int64_t) { flags_["sampled"] = "true"; },
      "Networks: the paper's mode, one pass on num_points samples, labels carried back to the other points "
      "(--carry-k; default: a prediction for every point)");
  option("--sampling", "sampling", "With --sampled: random (as in training, default) or fps");
  integer("--carry-k", "carry_k",
          "With --sampled: samples voting for each other point, weighted by distance and colour (default 4; 1 = "
          "nearest, the paper)");
  integer("--votes", "votes",
          "Networks: N passes rotated about the vertical axis by 360/N degrees each, as test-time augmentation "
          "(every-point mode: N covers, class probabilities averaged; --sampled: N samples, probabilities carried "
          "back and summed); N times the time (default 1)");
  cmd->add_option_function<std::string>(
      "--ensemble", [this](const std::string& v) { flags_["ensemble"] = io::find_model(v).string(); },
      "A second model (network or GBDT, default settings) whose per-point class probabilities are mixed with "
      "this model's; the label is the argmax of the mix");
  number("--ensemble-weight", "ensemble_weight", "With --ensemble: the second model's share (default 0.5)");
}

std::string GrapeSegmenterOptions::preset() const {
  const std::string preset = !preset_.empty() ? preset_ : flags_.count("model") ? "" : default_preset_;
  const std::string ext = std::filesystem::path(preset).extension().string();
  if ((ext == ".pt" || ext == ".json") && flags_.count("model"))
    throw Error(preset_flag_, "names a model file; give it or --model, not both");
  return preset;
}

pipeline::grape::SegmenterConfig GrapeSegmenterOptions::config() const {
  return pipeline::grape::grape_segmenter_config(preset(), flags_, "command line");
}

void GrapeSegmenterOptions::add_to_spec(pipeline::PipelineSpec& spec) const {
  spec.model = preset();
  for (const auto& [key, value] : flags_) spec.sets.push_back("segmenter." + key + "=" + value);
}

void GrapeSegmenterOptions::describe(const pipeline::grape::SegmenterConfig& cfg, nlohmann::json& j) {
  j["votes"] = cfg.votes;
  if (!cfg.ensemble.empty()) {
    j["ensemble"] = cfg.ensemble;
    j["ensemble_weight"] = cfg.ensemble_weight;
  }
}

}  // namespace cropsight::cli
