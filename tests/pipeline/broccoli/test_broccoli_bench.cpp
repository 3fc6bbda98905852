// pipeline::broccoli::bench (bench.hpp) on two simulated frames: which pipelines it times and with
// which settings (the model's own, the variety's presets, --set and the outlier switch over both),
// never how fast they ran.
#include <gtest/gtest.h>

#include "broccoli_sim_frames.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/config_yaml.hpp"
#include "cropsight/pipeline/broccoli/bench.hpp"
#include "cropsight/pipeline/broccoli/config.hpp"

namespace {
namespace pb = cropsight::pipeline::broccoli;

const std::vector<cropsight::RgbdFrame>& frames() {
  static const auto f = cropsight::testdata::simulate(cropsight::testdata::sim_preset("uk"), 7, 2);
  return f;
}

std::string shipped(const std::string& name) {
  return (cropsight::testing::source_dir() / "models" / (name + ".json")).string();
}

// A shipped preset's detector settings, as configs/NAME.yaml gives them.
pb::DetectorConfig preset_detector(const std::string& name) {
  pb::Config cfg;
  cropsight::apply_config(cfg, cropsight::io::load_config_map(cropsight::io::find_preset(name)), name);
  return cfg.detector;
}

// Each pipeline's detector settings against what the one config path gives for it.
TEST(BroccoliBench, TimesEveryPipelineWithTheModelsOrThePresetsSettings) {
  pb::BenchSpec spec;
  spec.model = shipped("broccoli-oes-uk");
  spec.sets = {"depth.max_depth=0.95", "sizing.hull_max_points=400"};
  spec.track = true;
  spec.repeat = 2;
  const pb::BenchResult r = pb::bench(spec, frames());

  ASSERT_EQ(r.detectors.size(), 3u);
  const pb::BenchedPipeline& oes = r.detectors.at("oes");
  const pb::BenchedPipeline& org = r.detectors.at("org");
  const pb::BenchedPipeline& fec = r.detectors.at("fec");
  // The model's own pipeline: what it records, then --set.
  EXPECT_EQ(oes.settings, "model");
  const auto model = pb::load_model(spec.model);
  pb::DetectorConfig own = pb::config_for_model(*model, {{"depth.max_depth", "0.95"}}, spec.model).detector;
  own.outliers.enabled = false;
  EXPECT_EQ(cropsight::dump_config(oes.detector), cropsight::dump_config(own));
  // The others: their uk presets (VFH features).
  EXPECT_EQ(org.settings, "preset broccoli-org-uk");
  EXPECT_EQ(org.detector.pipeline, pb::Variant::org);
  EXPECT_EQ(cropsight::dump_config(org.detector.org), cropsight::dump_config(preset_detector("broccoli-org-uk").org));
  EXPECT_EQ(fec.settings, "preset broccoli-fec-uk");
  EXPECT_EQ(fec.detector.pipeline, pb::Variant::fec);
  EXPECT_EQ(cropsight::dump_config(fec.detector.fec), cropsight::dump_config(preset_detector("broccoli-fec-uk").fec));
  for (const auto& [name, p] : r.detectors) {
    EXPECT_FLOAT_EQ(p.detector.depth.max_depth, 0.95f) << name;  // --set reaches every pipeline
    EXPECT_FALSE(p.detector.outliers.enabled) << name;           // no --sor
    EXPECT_EQ(p.detector.features, "vfh") << name;
    EXPECT_EQ(p.timing.frames, 4) << name;  // 2 frames x 2 passes
    EXPECT_FALSE(p.timing.stages.empty()) << name;
    EXPECT_TRUE(p.vs_pcl.has_value()) << name;
  }
  // The PCL reference: the FEC preset's settings, and no ratio to itself.
  ASSERT_TRUE(r.pcl_reference.has_value());
  EXPECT_EQ(r.pcl_reference->settings, "preset broccoli-fec-uk");
  EXPECT_EQ(cropsight::dump_config(r.pcl_reference->detector), cropsight::dump_config(fec.detector));
  EXPECT_FALSE(r.pcl_reference->vs_pcl.has_value());
  EXPECT_EQ(r.pcl_reference->timing.frames, 4);
  // Tracking: the OES pipeline's sizing keys with --set.
  ASSERT_TRUE(r.tracking.has_value());
  EXPECT_EQ(r.tracking->mapping.sizing.hull_max_points, 400);
  EXPECT_EQ(r.tracking->timing.frames, 4);
}

TEST(BroccoliBench, RunsOnlyThePipelinesAskedWithTheVarietysPresetsAndOutlierRemoval) {
  pb::BenchSpec spec;
  spec.model = shipped("broccoli-oes-uk");
  spec.variety = "spain";
  spec.pipelines = {"fec"};
  spec.sor = true;
  const pb::BenchResult r = pb::bench(spec, frames());
  ASSERT_EQ(r.detectors.size(), 1u);
  const pb::BenchedPipeline& fec = r.detectors.at("fec");
  EXPECT_EQ(fec.settings, "preset broccoli-fec-spain");
  EXPECT_EQ(cropsight::dump_config(fec.detector.fec),
            cropsight::dump_config(preset_detector("broccoli-fec-spain").fec));
  EXPECT_TRUE(fec.detector.outliers.enabled);
  EXPECT_EQ(fec.timing.frames, 2);
  EXPECT_FALSE(fec.vs_pcl.has_value());
  EXPECT_FALSE(r.pcl_reference.has_value());
  EXPECT_FALSE(r.tracking.has_value());
}

// A bad spec is refused before any model loads, naming the option.
TEST(BroccoliBench, BadSpecsNameTheirOption) {
  const auto where = [](const pb::BenchSpec& spec) {
    try {
      pb::bench(spec, frames());
    } catch (const cropsight::Error& e) {
      return e.where();
    }
    return std::string("no error");
  };
  pb::BenchSpec spec;
  spec.model = "no-such-model";
  spec.pipelines = {"oes", "pcll"};
  EXPECT_EQ(where(spec), "--pipelines");
  spec.pipelines = {"org"};
  spec.track = true;
  EXPECT_EQ(where(spec), "--track");
  spec.track = false;
  spec.variety = "france";
  EXPECT_EQ(where(spec), "--variety");
  spec.variety = "uk";
  spec.repeat = 0;
  EXPECT_EQ(where(spec), "--repeat");
}

}  // namespace
