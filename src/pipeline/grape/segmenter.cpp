#include "cropsight/pipeline/grape/segmenter.hpp"

#include "cropsight/core/error.hpp"
#include "cropsight/io/config_yaml.hpp"

namespace cropsight::pipeline::grape {

void SegmenterConfig::validate(const std::string& where) const {
  check_config(*this, where);
  if (sampling != "random" && sampling != "fps")
    throw Error(where, "'sampling' expects random or fps, got '" + sampling + "'");
  if (model.empty()) throw Error(where, "'model' is not set (a .pt network or a .json GBDT model file)");
}

SegmenterConfig load_segmenter_config(const std::filesystem::path& preset, const ConfigMap& overrides,
                                      const std::string& overrides_where) {
  SegmenterConfig cfg;
  const std::string where = preset.string();
  apply_config(cfg, io::load_config_map(preset), where);
  // A preset names its models relative to itself, so that it works from any working directory.
  for (std::string* path : {&cfg.model, &cfg.ensemble}) *path = io::relative_to_preset(preset, *path);
  check_config(cfg, where);
  apply_config(cfg, overrides, overrides_where);
  check_config(cfg, overrides_where);
  return cfg;
}

SegmenterConfig grape_segmenter_config(const std::string& preset_or_model, const ConfigMap& overrides,
                                       const std::string& overrides_where) {
  const std::string ext = std::filesystem::path(preset_or_model).extension().string();
  if (!preset_or_model.empty() && ext != ".pt" && ext != ".json")
    return load_segmenter_config(io::find_preset(preset_or_model), overrides, overrides_where);
  ConfigMap values = overrides;
  if (!preset_or_model.empty()) {  // a model file where a preset goes: that model, default settings
    if (values.count("model")) throw Error(preset_or_model, "is a model file; give it or a 'model' override, not both");
    values["model"] = preset_or_model;
  }
  SegmenterConfig cfg;
  apply_config(cfg, values, overrides_where);
  return cfg;
}

namespace {
// Checks `cfg` before any model is loaded (a bad value costs no model load), then loads it.
Model load_model(const SegmenterConfig& cfg, const std::string& where) {
  cfg.validate(where);
  return Model::load(cfg.model, cfg.threads);
}
}  // namespace

Segmenter::Segmenter(const SegmenterConfig& cfg, const std::string& where) : cfg_(cfg), model_(load_model(cfg, where)) {
  // Model's setters throw Error("grape model", ...); here the same rules name the key and
  // the config they came from.
  if (model_.kind() == "gbdt") {
    if (cfg.sampled) throw Error(where, "'sampled' is only for network models (a GBDT recipe fixes its own sampling)");
    if (cfg.votes > 1)
      throw Error(where, "'votes' above 1 is only for network models, got " + std::to_string(cfg.votes));
  } else {
    model_.set_sampled(cfg.sampled, cfg.sampling == "fps", cfg.carry_k);
    model_.set_votes(cfg.votes);
  }
  if (!cfg.ensemble.empty())
    model_.set_ensemble(std::make_shared<const Model>(Model::load(cfg.ensemble, cfg.threads)), cfg.ensemble_weight);
  else if (cfg.ensemble_weight != 0.5)
    throw Error(where, "'ensemble_weight' needs 'ensemble' (a second model)");
}

}  // namespace cropsight::pipeline::grape
