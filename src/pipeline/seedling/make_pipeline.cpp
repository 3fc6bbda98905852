#include "cropsight/pipeline/seedling/make_pipeline.hpp"

#include "cropsight/io/config_yaml.hpp"

namespace cropsight::pipeline::seedling {

std::unique_ptr<Pipeline> make_pipeline(const PipelineSpec& spec) {
  const std::string preset = spec.preset.empty() ? kDefaultPreset : spec.preset;
  Config cfg = load_config(preset);  // validated, errors name the preset file
  if (!spec.sets.empty()) {
    apply_config(cfg, io::load_preset_with_overrides("", spec.sets), "--set");
    cfg.validate("--set");
  }
  return std::make_unique<Pipeline>(std::move(cfg), preset);
}

}  // namespace cropsight::pipeline::seedling
