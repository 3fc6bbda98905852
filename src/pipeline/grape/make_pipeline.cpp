#include "cropsight/pipeline/grape/make_pipeline.hpp"

#include <filesystem>

#include "cropsight/core/error.hpp"
#include "cropsight/io/config_yaml.hpp"
#include "cropsight/nn/center_backend.hpp"

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

// The segmenter's keys (segmenter.*, from the preset or --set) taken out of `values`, without
// their prefix: they are laid over the segmenter preset or model the spec names.
ConfigMap take_segmenter_keys(ConfigMap& values) {
  ConfigMap segmenter;
  for (auto it = values.begin(); it != values.end();) {
    if (it->first.rfind(kSegmenterPrefix, 0) == 0) {
      segmenter[it->first.substr(std::string(kSegmenterPrefix).size())] = it->second;
      it = values.erase(it);
    } else {
      ++it;
    }
  }
  return segmenter;
}

SegmenterConfig segmenter_config(const PipelineSpec& spec, const ConfigMap& overrides) {
  const std::string source =
      spec.model.empty() ? (overrides.count("model") ? "" : kDefaultSegmenter) : segmenter_source(spec.model);
  SegmenterConfig cfg = grape_segmenter_config(source, overrides, "segmenter.* (preset or --set)");
  if (spec.threads > 0) cfg.threads = spec.threads;
  return cfg;
}

}  // namespace

SegmenterConfig segmenter_config(const PipelineSpec& spec) {
  ConfigMap values = spec_values(spec, kDefaultPreset);
  return segmenter_config(spec, take_segmenter_keys(values));
}

std::unique_ptr<Pipeline> make_pipeline(const PipelineSpec& spec) {
  const std::string where = spec_where(spec, kDefaultPreset);
  ConfigMap values = spec_values(spec, kDefaultPreset);
  const ConfigMap segmenter_keys = take_segmenter_keys(values);
  Config cfg;
  apply_config(cfg, values, where);
  cfg.validate(where);
  cfg.segmenter = segmenter_config(spec, segmenter_keys);
  Segmenter segmenter(cfg.segmenter, spec.model.empty() ? kDefaultSegmenter : spec.model);
  std::unique_ptr<Detector2D> detector;
  if (!spec.detector.empty())
    detector = nn::open_center_detector(spec.detector, cfg.detector.backend, std::max(1, cfg.segmenter.threads));
  return std::make_unique<Pipeline>(std::move(cfg), std::move(segmenter), std::move(detector), where);
}

}  // namespace cropsight::pipeline::grape
