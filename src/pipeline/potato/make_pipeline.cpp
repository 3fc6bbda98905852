#include "cropsight/pipeline/potato/make_pipeline.hpp"

#include "cropsight/io/config_yaml.hpp"

namespace cropsight::pipeline::potato {

Config spec_config(const PipelineSpec& spec) {
  ConfigMap sets = io::load_preset_with_overrides("", spec.sets);
  if (!spec.model.empty()) {
    sets["detector.backend"] = "onnx";
    sets["detector.onnx.model"] = io::find_model(spec.model).string();
  }
  return load_config(spec.preset.empty() ? kDefaultPreset : spec.preset, sets);
}

std::unique_ptr<Pipeline> make_pipeline(const PipelineSpec& spec) {
  return std::make_unique<Pipeline>(spec_config(spec), spec.preset.empty() ? kDefaultPreset : spec.preset);
}

}  // namespace cropsight::pipeline::potato
