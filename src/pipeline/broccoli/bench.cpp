#include "cropsight/pipeline/broccoli/bench.hpp"

#include <algorithm>

#include "cropsight/core/error.hpp"
#include "cropsight/io/config_yaml.hpp"
#include "cropsight/pipeline/broccoli/config.hpp"
#include "cropsight/pipeline/broccoli/timing.hpp"

namespace cropsight::pipeline::broccoli {

namespace {
bool asked(const BenchSpec& spec, const std::string& pipeline) {
  return std::find(spec.pipelines.begin(), spec.pipelines.end(), pipeline) != spec.pipelines.end();
}

std::string preset_name(const BenchSpec& spec, const std::string& pipeline) {
  return "broccoli-" + pipeline + "-" + spec.variety;
}

// The variety's preset of `pipeline`, then the overrides: sizing.* / tracking.* are checked here
// too, so that a typo is an error; the detector times with VFH (the one feature PCL computes) and
// the bench's outlier setting.
Config preset_config(const BenchSpec& spec, const std::string& pipeline, const ConfigMap& overrides) {
  const std::string name = preset_name(spec, pipeline);
  Config cfg;
  apply_config(cfg, io::load_config_map(io::find_preset(name)), name);
  apply_config(cfg, overrides, "--set");
  cfg.validate(name);
  cfg.detector.features = "vfh";
  cfg.detector.outliers.enabled = spec.sor;
  return cfg;
}

// The model's own pipeline: what the model records, then the overrides and the outlier setting.
Config model_config(const BenchSpec& spec, const learning::Model& model, const std::string& file,
                    const ConfigMap& overrides) {
  Config cfg = config_for_model(model, overrides, file, "--set");
  cfg.detector.outliers.enabled = spec.sor;
  return cfg;
}
}  // namespace

Config variant_config(const BenchSpec& spec, Variant variant) {
  return preset_config(spec, config_name(variant), io::load_preset_with_overrides(spec.preset, spec.sets));
}

void BenchSpec::validate() const {
  if (repeat < 1) throw Error("--repeat", "must be at least 1");
  if (variety != "uk" && variety != "spain") throw Error("--variety", "must be uk or spain");
  for (const auto& p : pipelines)
    if (p != "oes" && p != "org" && p != "fec" && p != "pcl")
      throw Error("--pipelines", "unknown pipeline '" + p + "' (oes, org, fec, pcl)");
  if (track && !asked(*this, "oes")) throw Error("--track", "times the OES detections: --pipelines must include oes");
}

BenchResult bench(const BenchSpec& spec, const std::vector<RgbdFrame>& frames) {
  spec.validate();
  const std::string file = io::find_model(spec.model).string();
  const std::shared_ptr<const learning::Model> model = load_model(file);
  const ConfigMap overrides = io::load_preset_with_overrides(spec.preset, spec.sets);
  BenchResult out;
  for (const Variant variant : {Variant::oes, Variant::org, Variant::fec}) {
    const std::string name = config_name(variant);
    if (!asked(spec, name)) continue;
    const bool own = model->info.pipeline == name;
    const Config cfg = own ? model_config(spec, *model, file, overrides) : preset_config(spec, name, overrides);
    BenchedPipeline p{own ? "model" : "preset " + preset_name(spec, name), cfg.detector, {}, {}};
    Detector det(cfg.detector);
    det.set_model(model_for_variant(model, variant, file), file);
    p.timing = time_detector(det, frames, spec.repeat);
    if (variant == Variant::oes && spec.track)
      out.tracking = BenchedTracking{cfg.mapping(), time_tracking(det, cfg.mapping(), frames, spec.repeat), {}};
    out.detectors[name] = std::move(p);
  }
  if (asked(spec, "pcl")) {
    const Config cfg = preset_config(spec, "fec", overrides);
    out.pcl_reference = BenchedPipeline{"preset " + preset_name(spec, "fec"), cfg.detector, {}, {}};
    PclReferencePipeline pcl(cfg.detector, model, file);
    out.pcl_reference->timing = time_pcl_reference(pcl, frames, spec.repeat);
    for (auto& [name, p] : out.detectors) p.vs_pcl = time_ratio(out.pcl_reference->timing, p.timing);
  }
  if (out.tracking) out.tracking->vs_oes = time_ratio(out.tracking->timing, out.detectors.at("oes").timing);
  return out;
}

}  // namespace cropsight::pipeline::broccoli
