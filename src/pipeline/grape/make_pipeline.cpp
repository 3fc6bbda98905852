#include "cropsight/pipeline/grape/make_pipeline.hpp"

#include <filesystem>

#include "cropsight/core/error.hpp"
#include "cropsight/io/config_yaml.hpp"
#include "cropsight/nn/center_onnx.hpp"

namespace cropsight::pipeline::grape {

namespace {

constexpr const char* kSegmenterPrefix = "segmenter.";

// What grape_segmenter_config takes: a file as named, else a shipped model of that name
// (models/NAME.*; configs/ holds training presets of the same names, e.g. grape-gbdt-fast), else
// a segmenter preset (configs/NAME.yaml, e.g. grape-best).
std::string segmenter_source(const std::string& name) {
  if (std::filesystem::exists(name)) return name;
  try {
    return io::find_model(name).string();
  } catch (const Error&) {
  }
  return name;
}

// The spec's sets split: the pipeline's keys, and the segmenter's without their prefix.
std::pair<std::vector<std::string>, ConfigMap> split_sets(const PipelineSpec& spec) {
  std::vector<std::string> pipeline_sets;
  ConfigMap segmenter;
  for (const std::string& s : spec.sets) {
    auto [key, value] = parse_assignment(s);
    if (key.rfind(kSegmenterPrefix, 0) == 0)
      segmenter[key.substr(std::string(kSegmenterPrefix).size())] = value;
    else
      pipeline_sets.push_back(s);
  }
  return {pipeline_sets, segmenter};
}

}  // namespace

SegmenterConfig segmenter_config(const PipelineSpec& spec) {
  const ConfigMap overrides = split_sets(spec).second;
  const std::string source =
      spec.model.empty() ? (overrides.count("model") ? "" : kDefaultSegmenter) : segmenter_source(spec.model);
  SegmenterConfig cfg = grape_segmenter_config(source, overrides, "--set segmenter.*");
  if (spec.threads > 0) cfg.threads = spec.threads;
  return cfg;
}

std::unique_ptr<Pipeline> make_pipeline(const PipelineSpec& spec) {
  PipelineSpec pipeline_spec = spec;
  pipeline_spec.sets = split_sets(spec).first;
  const std::string where = spec_where(pipeline_spec, kDefaultPreset);
  Config cfg;
  apply_config(cfg, spec_values(pipeline_spec, kDefaultPreset), where);
  cfg.validate(where);
  const SegmenterConfig scfg = segmenter_config(spec);
  Segmenter segmenter(scfg, spec.model.empty() ? kDefaultSegmenter : spec.model);
  std::unique_ptr<Detector2D> detector;
  if (!spec.detector.empty())
    detector = nn::load_center_detector(io::find_model(spec.detector).string(), std::max(1, scfg.threads));
  return std::make_unique<Pipeline>(std::move(cfg), std::move(segmenter), std::move(detector), where);
}

}  // namespace cropsight::pipeline::grape
