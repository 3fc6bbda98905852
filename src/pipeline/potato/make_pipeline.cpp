#include "cropsight/pipeline/potato/make_pipeline.hpp"

#include "cropsight/io/config_yaml.hpp"

namespace cropsight::pipeline::potato {

PotatoPipelineConfig spec_config(const PipelineSpec& spec) {
  ConfigMap sets = io::load_preset_with_overrides("", spec.sets);
  if (!spec.model.empty()) {
    sets["detector.backend"] = "onnx";
    sets["detector.onnx.model"] = io::find_model(spec.model).string();
  }
  return load_potato_config(spec.preset.empty() ? kDefaultPreset : spec.preset, sets);
}

std::unique_ptr<PotatoPipeline> make_pipeline(const PipelineSpec& spec) {
  return std::make_unique<PotatoPipeline>(spec_config(spec), spec.preset.empty() ? kDefaultPreset : spec.preset);
}

}  // namespace cropsight::pipeline::potato
