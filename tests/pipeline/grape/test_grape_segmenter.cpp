#include <gtest/gtest.h>

#include <fstream>

#include "cropsight/core/error.hpp"
#include "cropsight/pipeline/grape/segmenter.hpp"
#include "testing/testing.hpp"

namespace {
using cropsight::testing::error_message;
using namespace cropsight;
// Declarations, not `using namespace cropsight::pipeline`: the tests compile as unity batches,
// where a using-directive in the shared anonymous namespace reaches the next files (the potato
// tests' helper potato() then clashes with namespace pipeline::potato).
using cropsight::pipeline::grape::load_segmenter_config;
using cropsight::pipeline::grape::Segmenter;
using cropsight::pipeline::grape::SegmenterConfig;
namespace fs = std::filesystem;

TEST(GrapeSegmenterConfig, ShippedPresetsNameTheirModelsRelativeToThemselves) {
  const fs::path configs = cropsight::testing::source_dir() / "configs";
  const auto best = pipeline::grape::load_segmenter_config(configs / "grape-best.yaml");
  EXPECT_TRUE(best.sampled);
  EXPECT_EQ(best.votes, 6);
  EXPECT_EQ(best.carry_k, 4);
  EXPECT_DOUBLE_EQ(best.ensemble_weight, 0.5);
  EXPECT_EQ(fs::path(best.model).filename(), "grape-pointresnet.pt");
  EXPECT_EQ(fs::path(best.ensemble).filename(), "grape-gbdt-fast4096.json");
  EXPECT_TRUE(fs::exists(best.model) && fs::exists(best.ensemble)) << best.model << " " << best.ensemble;
  const auto fold1 = pipeline::grape::load_segmenter_config(configs / "grape-best-fold1.yaml");
  EXPECT_EQ(fs::path(fold1.model).filename(), "grape-pointresnet-fold1.pt");
  EXPECT_EQ(fs::path(fold1.ensemble).filename(), "grape-gbdt-fast4096-fold1.json");
  const auto paper = pipeline::grape::load_segmenter_config(configs / "grape-paper.yaml", {{"votes", "3"}});
  EXPECT_EQ(paper.carry_k, 1);
  EXPECT_TRUE(paper.ensemble.empty());
  EXPECT_EQ(paper.votes, 3);  // overrides apply after the preset
}

TEST(GrapeSegmenterConfig, ErrorsNameTheKeyAndWhereItCameFrom) {
  cropsight::testing::TempDir t;
  std::ofstream(t / "p.yaml") << "model: m.pt\nensemble_weight: 1.5\n";
  EXPECT_NE(error_message([&] {
              pipeline::grape::load_segmenter_config(t / "p.yaml");
            }).find("p.yaml: 'ensemble_weight' must be at most 1"),
            std::string::npos);
  std::ofstream(t / "q.yaml") << "model: m.pt\nvotes: many\n";
  EXPECT_NE(error_message([&] {
              pipeline::grape::load_segmenter_config(t / "q.yaml");
            }).find("q.yaml: 'votes' expects a number"),
            std::string::npos);
  std::ofstream(t / "r.yaml") << "model: m.pt\n";
  EXPECT_NE(error_message([&] {
              pipeline::grape::load_segmenter_config(t / "r.yaml", {{"carry_k", "0"}}, "flags");
            }).find("flags: 'carry_k' must be at least 1"),
            std::string::npos);
  pipeline::grape::SegmenterConfig c;
  EXPECT_NE(error_message([&] { c.validate("cfg"); }).find("cfg: 'model' is not set"), std::string::npos);
  c.model = "m.pt";
  c.sampling = "grid";
  EXPECT_NE(error_message([&] { c.validate("cfg"); }).find("cfg: 'sampling' expects random or fps"), std::string::npos);
}

TEST(GrapeSegmenter, AGbdtTakesNoNetworkModeAndAWeightNeedsAPartner) {
  pipeline::grape::SegmenterConfig c;
  c.model = (cropsight::testing::source_dir() / "models" / "grape-gbdt-fast.json").string();
  c.threads = 1;
  EXPECT_EQ(pipeline::grape::Segmenter(c, "cfg").model().kind(), "gbdt");
  c.sampled = true;
  EXPECT_NE(
      error_message([&] { pipeline::grape::Segmenter(c, "cfg"); }).find("cfg: 'sampled' is only for network models"),
      std::string::npos);
  c.sampled = false;
  c.votes = 2;
  EXPECT_NE(error_message([&] { pipeline::grape::Segmenter(c, "cfg"); }).find("cfg: 'votes'"), std::string::npos);
  c.votes = 1;
  c.ensemble_weight = 0.3;
  EXPECT_NE(
      error_message([&] { pipeline::grape::Segmenter(c, "cfg"); }).find("cfg: 'ensemble_weight' needs 'ensemble'"),
      std::string::npos);
  c.ensemble = c.model;  // an ensemble with itself: the same labels as the model alone
  const pipeline::grape::Segmenter both(c, "cfg");
  c.ensemble.clear(), c.ensemble_weight = 0.5;
  const pipeline::grape::Segmenter one(c, "cfg");
  Cloud cloud;
  for (int i = 0; i < 300; ++i) {
    const float a = 0.02f * float(i);
    cloud.points.emplace_back(0.5f * std::cos(a), 0.5f * std::sin(a), 0.001f * float(i % 7));
    cloud.normals.emplace_back(0, 0, 1);
    cloud.colors.emplace_back(i < 150 ? 0.1f : 0.3f, i < 150 ? 0.1f : 0.7f, 0.2f);
  }
  EXPECT_EQ(both.segment(cloud), one.segment(cloud));
}
}  // namespace
