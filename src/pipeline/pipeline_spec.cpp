#include "cropsight/pipeline/pipeline_spec.hpp"

#include "cropsight/io/config_yaml.hpp"

namespace cropsight::pipeline {

ConfigMap spec_values(const PipelineSpec& spec, const std::string& default_preset) {
  return io::load_preset_with_overrides(spec.preset.empty() ? default_preset : spec.preset, spec.sets);
}

std::string spec_where(const PipelineSpec& spec, const std::string& default_preset) {
  const std::string preset = spec.preset.empty() ? default_preset : spec.preset;
  if (preset.empty()) return "--set";
  return spec.sets.empty() ? preset : preset + " / --set";
}

}  // namespace cropsight::pipeline
