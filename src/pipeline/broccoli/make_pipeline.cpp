#include "cropsight/pipeline/broccoli/make_pipeline.hpp"

#include "cropsight/io/config_yaml.hpp"

namespace cropsight::pipeline::broccoli {

std::unique_ptr<Pipeline> make_pipeline(const PipelineSpec& spec) {
  const std::string file = io::find_model(spec.model.empty() ? kDefaultModel : spec.model).string();
  std::shared_ptr<const learning::Model> model = load_model(file);
  const Config cfg = config_for_model(*model, spec_values(spec, ""), file, spec_where(spec, ""));
  return std::make_unique<Pipeline>(cfg, std::move(model), file);
}

}  // namespace cropsight::pipeline::broccoli
