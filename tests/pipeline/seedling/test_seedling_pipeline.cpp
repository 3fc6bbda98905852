// The seedling pipeline (pipeline::seedling::Pipeline and its steps), its config and its data-set reader, on
// scenes rendered by the seedling simulator.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>

#include "cropsight/core/error.hpp"
#include "cropsight/pipeline/seedling/eval.hpp"
#include "cropsight/pipeline/seedling/pipeline.hpp"
#include "cropsight/pipeline/seedling/steps.hpp"
#include "cropsight/pipeline/seedling/truth.hpp"
#include "cropsight/sim/seedling/seedling_sim.hpp"
#include "pipeline/seedling/sim_truth.hpp"
#include "testing/testing.hpp"

using namespace cropsight;
using namespace cropsight::pipeline;

namespace fs = std::filesystem;

namespace {

// Runs `f`, expecting a cropsight::Error whose message contains `what`.
template <class F>
void expect_throw_naming(F&& f, const std::string& what) {
  try {
    f();
    ADD_FAILURE() << "no error; expected one naming " << what;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
  }
}

// The shipped default preset, configs/seedling.yaml (census engine, excess-green test).
pipeline::seedling::Config default_preset() { return pipeline::seedling::load_config("seedling"); }

// The detection found the simulated seedling: top-view IoU >= 0.5, envelope volume within 30 %.
void expect_recognised(const pipeline::seedling::FrameResult& d, const sim::SeedlingPair& p,
                       const stereo::RectifiedGeometry& g, int k) {
  ASSERT_TRUE(d.found) << "pair " << k;
  const auto s = pipeline::seedling::score(d, cropsight::testing::seedling_truth(p), g);
  EXPECT_GE(s.iou, 0.5) << "pair " << k;
  EXPECT_NEAR(s.volume_ratio, 1.0, 0.3) << "pair " << k;
}

sim::SeedlingSimConfig fast_sim() {
  sim::SeedlingSimConfig cfg;
  cfg.supersample = 1;
  return cfg;
}

}  // namespace

TEST(SeedlingPipeline, RecognisesSimulatedSeedlings) {
  const sim::SeedlingSimConfig cfg = fast_sim();
  const stereo::RectifiedGeometry g = sim::rectified_geometry(cfg.rig());
  const pipeline::seedling::Pipeline seedlings{pipeline::seedling::Config{}};
  for (int k = 0; k < 2; ++k) {
    const auto p = sim::simulate_seedling_pair(cfg, 4242, k);
    const auto det = seedlings.process(p.left, p.right, g);
    ASSERT_TRUE(det.found);
    EXPECT_EQ(det.points_sampled, 4096);
    const auto s = pipeline::seedling::score(det, cropsight::testing::seedling_truth(p), g);
    EXPECT_GE(s.iou, 0.5) << "pair " << k;
    EXPECT_NEAR(s.volume_ratio, 1.0, 0.35) << "pair " << k;
    // The stages a caller times, in the paper's order.
    std::vector<std::string> names;
    for (const auto& st : det.timer.stages()) names.push_back(st.name);
    EXPECT_EQ(names, (std::vector<std::string>{"disparity", "reconstruct", "plane", "sample", "gmm", "recognise",
                                               "outlier", "output"}));
  }
  ColorImage small(100, 80);
  EXPECT_THROW(seedlings.process(small, small, g), Error);
}

// The census engine raises scattered soil pixels above the height threshold; the image-space
// opening of the candidate mask must remove them without losing the plant.
TEST(SeedlingPipeline, CandidateOpeningDropsCensusSoilSpeckles) {
  const sim::SeedlingSimConfig cfg = fast_sim();
  const stereo::RectifiedGeometry g = sim::rectified_geometry(cfg.rig());
  // The default preset, colour test off, opening switched off and on.
  pipeline::seedling::Config sc = default_preset();
  ASSERT_EQ(sc.disparity.engine, "census");
  sc.candidate_min_exg = -1.0;
  for (int k = 0; k < 2; ++k) {
    const auto p = sim::simulate_seedling_pair(cfg, 4242, k);
    sc.candidate_open = 0;
    const auto raw = pipeline::seedling::Pipeline(sc).process(p.left, p.right, g);
    sc.candidate_open = 1;
    const auto opened = pipeline::seedling::Pipeline(sc).process(p.left, p.right, g);
    EXPECT_LT(opened.points_candidates, raw.points_candidates) << "pair " << k;
    expect_recognised(opened, p, g, k);
  }
}

// Soil pixels next to a leaf edge take the leaf's disparity from the matching window; they are
// soil-coloured. The preset's excess-green test must take them out of the seedling's dense points
// (fewer of its pixels outside the true seedling mask) while keeping the seedling itself.
TEST(SeedlingPipeline, ExcessGreenTestDropsFattenedSoilPixels) {
  const sim::SeedlingSimConfig cfg = fast_sim();
  const stereo::RectifiedGeometry g = sim::rectified_geometry(cfg.rig());
  pipeline::seedling::Config sc = default_preset();
  ASSERT_GT(sc.candidate_min_exg, -1.0) << "the default preset is expected to use the colour test";
  const double exg = sc.candidate_min_exg;
  auto outside = [](const pipeline::seedling::FrameResult& d, const GrayImage& truth) {
    int n = 0;
    for (int px : d.pixels) n += truth.data[std::size_t(px)] == 0;
    return d.pixels.empty() ? 1.0 : double(n) / double(d.pixels.size());
  };
  for (int k = 0; k < 2; ++k) {
    const auto p = sim::simulate_seedling_pair(cfg, 4242, k);
    sc.candidate_min_exg = -1.0;
    const auto off = pipeline::seedling::Pipeline(sc).process(p.left, p.right, g);
    sc.candidate_min_exg = exg;
    const auto on = pipeline::seedling::Pipeline(sc).process(p.left, p.right, g);
    ASSERT_TRUE(off.found && on.found) << "pair " << k;
    EXPECT_LT(on.points_candidates, off.points_candidates) << "pair " << k;
    EXPECT_LT(outside(on, p.mask), outside(off, p.mask)) << "pair " << k;
    EXPECT_LT(outside(on, p.mask), 0.05) << "pair " << k;
    expect_recognised(on, p, g, k);
  }
}

// Soil plane step: a tilted plane with 30 % of the points raised (plants) is recovered, its
// normal pointing towards the camera at the origin.
TEST(SeedlingSteps, SoilPlaneIgnoresPlantsAndFacesTheCamera) {
  const Eigen::Vector3d n = Eigen::Vector3d(0.1, -0.9, -0.3).normalized();
  const double d = 0.6;  // the camera (origin) is 0.6 m above the soil
  const Eigen::Vector3d e1 = n.unitOrthogonal(), e2 = n.cross(e1), base = -d * n;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-0.3, 0.3), h(0.02, 0.2);
  std::vector<Eigen::Vector3f> pts;
  for (int i = 0; i < 5000; ++i)
    pts.push_back((base + u(rng) * e1 + u(rng) * e2 + (i % 10 < 3 ? h(rng) : 0.0) * n).cast<float>());
  const seedling::SoilPlane pl = seedling::fit_soil_plane(pts, pipeline::seedling::Config{}, "test");
  EXPECT_GT(pl.n.dot(n), 0.9999);
  EXPECT_NEAR(pl.d, d, 1e-4);
  const auto hts = seedling::heights_above(pts, pl);
  EXPECT_NEAR(hts[5], 0.0, 1e-3);  // soil (i % 10 >= 3); points 0-2 are raised
  EXPECT_GT(hts[0] + hts[1] + hts[2], 0.06);
  expect_throw_naming(
      [&] {
        seedling::fit_soil_plane({pts[0], pts[1]}, pipeline::seedling::Config{}, "three");
      },
      "three");
}

// Recognition rule on hand-made components: the highest large component seeds, a touching one of
// enough height joins, a distant one and a low one do not.
TEST(SeedlingSteps, ComponentSelectionFollowsTheRule) {
  segmentation::GmmResult gmm;
  gmm.model.weights.assign(4, 0.25);
  std::vector<Eigen::Vector3f> pts;
  std::vector<float> height;
  auto add = [&](int label, float x, float h, int n) {
    for (int i = 0; i < n; ++i) {
      pts.emplace_back(x + 0.001f * float(i), 0, 0);
      height.push_back(h);
      gmm.labels.push_back(label);
    }
  };
  pipeline::seedling::Config cfg;  // min_component_points 15, height_ratio 0.3, join_distance 0.015
  add(0, 0.00f, 0.10f, 20);        // seed: highest; spans x 0 .. 0.019
  add(1, 0.025f, 0.05f, 20);       // touches the seed (0.006 m gap), high enough: joins
  add(2, 0.50f, 0.09f, 20);        // high but far away: a weed
  add(3, 0.046f, 0.01f, 20);       // touches component 1 but too low (0.1 < 0.3 x seed)
  ASSERT_EQ(gmm.model.size(), 4);
  const auto chosen = seedling::select_components(pts, height, gmm, cfg);
  EXPECT_EQ(chosen, (std::vector<int>{0, 1}));
  EXPECT_EQ(seedling::points_of_components(pts, gmm.labels, chosen).size(), 40u);
  cfg.min_component_points = 21;  // no component is large enough: nothing is recognised
  EXPECT_TRUE(seedling::select_components(pts, height, gmm, cfg).empty());
}

// A leaf whose petiole was lost: 2 cm below the seed leaf and 1 cm beside it. In 3D it is 2.2 cm
// away (> join_distance), seen from above 1 cm: it joins with join_top_view only.
TEST(SeedlingSteps, TopViewJoinKeepsALeafWhosePetioleWasLost) {
  segmentation::GmmResult gmm;
  gmm.model.weights.assign(2, 0.5);
  std::vector<Eigen::Vector3f> pts;
  std::vector<float> height;
  const Eigen::Vector3f up(0, 0, -1);  // the soil normal points towards the camera at the origin
  for (int i = 0; i < 20; ++i) {
    pts.push_back(Eigen::Vector3f(0.001f * float(i), 0, 0.5f) + 0.08f * up);  // seed: 8 cm high
    height.push_back(0.08f);
    gmm.labels.push_back(0);
  }
  for (int i = 0; i < 20; ++i) {
    pts.push_back(Eigen::Vector3f(0.029f + 0.001f * float(i), 0, 0.5f) + 0.06f * up);  // 6 cm high
    height.push_back(0.06f);
    gmm.labels.push_back(1);
  }
  pipeline::seedling::Config cfg;
  ASSERT_TRUE(cfg.join_top_view);
  EXPECT_EQ(seedling::select_components(pts, height, gmm, cfg), (std::vector<int>{0, 1}));
  cfg.join_top_view = false;
  EXPECT_EQ(seedling::select_components(pts, height, gmm, cfg), (std::vector<int>{0}));
}

TEST(SeedlingConfig, ErrorsNameTheKeyAndPresetsLoad) {
  pipeline::seedling::Config s;
  s.gmm.tolerance = -1;
  expect_throw_naming([&] { s.validate("x"); }, "'gmm.tolerance'");
  expect_throw_naming([&] { pipeline::seedling::Pipeline{s}; }, "'gmm.tolerance'");
  s = pipeline::seedling::Config{};
  s.topview_cell = 1e-9;
  expect_throw_naming([&] { s.validate("x"); }, "'topview_cell'");
  EXPECT_NO_THROW(pipeline::seedling::Config{}.validate("x"));
  // The default preset is the struct's defaults written down; the paper's differs in engine and
  // has no colour test.
  const pipeline::seedling::Config def = pipeline::seedling::load_config("seedling"), none{};
  EXPECT_EQ(def.disparity.engine, none.disparity.engine);
  EXPECT_EQ(def.disparity.census_p1, none.disparity.census_p1);
  EXPECT_EQ(def.disparity.census_p2, none.disparity.census_p2);
  EXPECT_EQ(def.disparity.census_p2_step, none.disparity.census_p2_step);
  EXPECT_EQ(def.candidate_min_exg, none.candidate_min_exg);
  const pipeline::seedling::Config paper = pipeline::seedling::Pipeline::from_preset("seedling-paper").config();
  EXPECT_EQ(paper.disparity.engine, "opencv");
  EXPECT_EQ(paper.candidate_min_exg, -1.0);
  EXPECT_FALSE(paper.join_top_view);
  cropsight::testing::TempDir tmp;
  std::ofstream(tmp / "bad.yaml") << "gmm:\n  components: 0\n";
  expect_throw_naming([&] { pipeline::seedling::load_config((tmp / "bad.yaml").string()); }, "bad.yaml");
  expect_throw_naming([&] { pipeline::seedling::load_config((tmp / "bad.yaml").string()); }, "'gmm.components'");
}

// The reader of the simulator's data set returns the truth the simulator rendered.
TEST(SeedlingTruth, ReadsWhatTheSimulatorWrote) {
  cropsight::testing::TempDir tmp;
  const sim::SeedlingSimConfig cfg = fast_sim();
  sim::write_seedling_dataset(tmp / "d", cfg, 1, 77, 0);
  stereo::save_calibration(tmp / "d" / "rig.yaml", sim::ideal_calibration(cfg.rig()));
  const pipeline::seedling::Dataset ds = pipeline::seedling::open_dataset(tmp / "d");
  ASSERT_EQ(ds.pairs.size(), 1u);
  EXPECT_NEAR(ds.geometry.f, cfg.rig().f, 1e-9);  // through rig.yaml's text
  EXPECT_DOUBLE_EQ(ds.geometry.baseline, cfg.rig().baseline());
  const pipeline::seedling::Truth t = pipeline::seedling::read_truth(ds.pairs[0]);
  const sim::SeedlingPair p = sim::simulate_seedling_pair(cfg, 77, 0);
  EXPECT_DOUBLE_EQ(t.envelope.volume(), p.envelope.volume());
  EXPECT_DOUBLE_EQ(t.plane_d, p.plane_d);
  EXPECT_TRUE(t.plane_normal.isApprox(p.plane_normal));
  EXPECT_EQ(t.mask.data, p.mask.data);
  ASSERT_EQ(t.disparity.size(), p.disparity.size());
  for (std::size_t i = 0; i < p.disparity.size(); ++i) {
    if (std::isfinite(p.disparity.data[i])) {
      EXPECT_NEAR(t.disparity.data[i], p.disparity.data[i], 1.0 / 512) << i;
    }
  }
  // A truth without a plane fails naming the file and the key.
  std::ofstream(ds.pairs[0] / "truth.json") << R"({"envelope": {"length_m": 0.1, "width_m": 0.1, "height_m": 0.1}})";
  expect_throw_naming([&] { pipeline::seedling::read_truth(ds.pairs[0]); }, "truth.json");
  expect_throw_naming([&] { pipeline::seedling::read_truth(ds.pairs[0]); }, "plane");
  expect_throw_naming([&] { pipeline::seedling::open_dataset(tmp / "none"); }, "data folder not found");
}

// The evaluator's figures: a detection equal to the truth scores IoU 1, and means are per pair.
TEST(SeedlingEvaluator, PerfectDetectionScoresOneAndMeansArePerPair) {
  const sim::SeedlingSimConfig cfg = fast_sim();
  const stereo::RectifiedGeometry g = sim::rectified_geometry(cfg.rig());
  const sim::SeedlingPair p = sim::simulate_seedling_pair(cfg, 4242, 0);
  const pipeline::seedling::Truth truth = cropsight::testing::seedling_truth(p);
  pipeline::seedling::FrameResult perfect;
  stereo::DisparityImage masked = p.disparity;
  for (std::size_t i = 0; i < masked.size(); ++i)
    if (!p.mask.data[i]) masked.data[i] = std::nanf("");
  perfect.points = stereo::reconstruct(masked, g).points;
  perfect.envelope = p.envelope;
  perfect.found = true;
  pipeline::seedling::Evaluator ev(segmentation::GmmConfig{});
  const auto& row = ev.add("a", perfect, truth, g);
  EXPECT_DOUBLE_EQ(row.score.iou, 1.0);
  EXPECT_DOUBLE_EQ(row.score.sensitivity, 1.0);
  EXPECT_DOUBLE_EQ(row.score.volume_ratio, 1.0);
  ev.add("b", pipeline::seedling::FrameResult{}, truth, g);  // nothing found: IoU 0, volume 0
  const pipeline::seedling::Figures e = ev.figures();
  EXPECT_EQ(e.pairs, 2);
  EXPECT_DOUBLE_EQ(e.recognition_rate, 0.5);
  EXPECT_DOUBLE_EQ(e.sensitivity, 0.5);
  EXPECT_DOUBLE_EQ(e.volume_ratio, 0.5);
  EXPECT_EQ(e.opencv_runs, 0);
  ASSERT_EQ(e.per_pair.size(), 2u);
  EXPECT_EQ(e.per_pair[1].pair, "b");
}
