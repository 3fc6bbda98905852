// The broccoli detector's steps (pipeline/broccoli/steps/) used one by one, as a caller that
// composes its own pipeline would: they give what Detector::process gives, and the frame state
// they share holds what its header says.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <utility>
#include <vector>

#include "broccoli_sim_frames.hpp"
#include "cropsight/pipeline/broccoli/config.hpp"
#include "cropsight/pipeline/broccoli/detector.hpp"
#include "cropsight/pipeline/broccoli/steps/crease_split.hpp"
#include "cropsight/pipeline/broccoli/steps/head_completion.hpp"
#include "testing/testing.hpp"

using namespace cropsight;
using namespace cropsight::pipeline::broccoli;

namespace broccoli_steps_test {
std::shared_ptr<const learning::Model> general_model() {
  return load_model(cropsight::testing::source_dir() / "models" / "broccoli-oes-general.json");
}

// Frames 9-11 of a wide validation field (`simulate broccoli --variety random-wide --seed 6111`),
// where the crease split frees heads joined to leaves; shared by the tests (rendering is the slow
// part).
const std::vector<RgbdFrame>& frames() {
  static const auto f = [] {
    sim::BroccoliSimulator field(testdata::sim_preset("random-wide"), 6111, 12);
    std::vector<RgbdFrame> out;
    for (int i = 9; i < 12; ++i) out.push_back(field.render(i));
    return out;
  }();
  return f;
}

// The OES steps of `cfg` composed by hand over one FrameState, in Detector::process's order (no
// CNN: the general model does not use it).
struct ByHand {
  ByHand(const DetectorConfig& cfg, std::shared_ptr<const learning::Model> model)
      : cloud(cfg.depth, cfg.denoise, cfg.range, cfg.oes),
        normals(cfg.normals, !(cfg.edges.high_curvature_threshold > 0.0f)),
        edges(cfg.edges, true),
        clustering(cfg.pipeline, cfg.org, cfg.fec, cfg.outliers),
        description(cfg.features, cfg.feature_options, cfg.detection.min_normal_points,
                    cfg.detection.split_oversized_above),
        classification(cfg.detection.score_margin),
        split(cfg.detection, description, classification),
        completion({cfg.detection.grow_tolerance, cfg.detection.grow_radius}) {
    classification.set_model(std::move(model));
  }
  void process(const RgbdFrame& frame) {
    s.conditions = cloud.run(frame, s.cloud, timer);
    normals.before_clustering(s.cloud, timer);
    std::vector<Segment> segments =
        clustering.run(s.cloud, edges.run(s.cloud, timer), s.conditions.oes, s.owners, timer);
    normals.after_clustering(s.cloud, s.owners, timer);
    description.run(segments, s.cloud, s.candidates, timer);
    classification.run(s.candidates, timer);
    unsplit.clear();
    for (const Candidate& c : s.candidates.active()) unsplit.push_back(c.segment.indices);
    split.refine(frame, s, timer);
    for (std::size_t k = 0; k < s.candidates.size(); ++k)
      split_changed += k >= unsplit.size() || s.candidates[k].segment.indices != unsplit[k];
    completion.refine(frame, s, timer);
  }

  steps::CloudStep cloud;
  steps::NormalsStep normals;
  steps::EdgesStep edges;
  steps::ClusteringStep clustering;
  steps::DescriptionStep description;
  steps::ClassificationStep classification;
  steps::CreaseSplit split;
  steps::HeadCompletion completion;
  steps::FrameState s;
  StageTimer timer;
  std::vector<std::vector<int>> unsplit;  // the candidates' pixels before the crease split
  int split_changed = 0;                  // candidates the split replaced or added, all frames
};
}  // namespace broccoli_steps_test

using namespace broccoli_steps_test;

// Every step of the general model (denoise, soil window, lazy normals, debris pass, crease split,
// completion) gives, composed by hand, the detector's candidates.
TEST(BroccoliSteps, ComposedByHandTheyGiveTheDetectorsCandidates) {
  const auto model = general_model();
  const DetectorConfig cfg = config_for_model(*model, {}, "general").detector;
  ASSERT_GT(cfg.detection.split_concave_angle_deg, 0.0f);
  ASSERT_GT(cfg.detection.grow_tolerance, 0.0f);
  Detector detector(cfg);
  detector.set_model(model);
  ByHand steps(cfg, model);
  for (const RgbdFrame& frame : broccoli_steps_test::frames()) {
    const auto expected = detector.process(frame);
    steps.process(frame);
    const auto got = steps.s.candidates.active();
    ASSERT_EQ(got.size(), expected.size()) << "frame " << frame.index;
    for (std::size_t k = 0; k < got.size(); ++k) {
      EXPECT_EQ(got[k].segment.indices, expected[k].segment.indices);
      EXPECT_EQ(got[k].features, expected[k].features);
      EXPECT_EQ(got[k].score, expected[k].score);
      EXPECT_EQ(got[k].head, expected[k].head);
    }
    EXPECT_EQ(steps.s.conditions.soil_depth, detector.soil_depth());
    EXPECT_EQ(steps.s.conditions.noise_sigma, detector.noise_sigma());
  }
  EXPECT_GT(steps.split_changed, 0) << "the crease split had work on these frames";
  for (const char* stage : {"cloud", "denoise", "normals", "edges", "clustering", "features", "classify", "completion"})
    EXPECT_GT(steps.timer.ms(stage), 0.0) << stage;
}

// After the clustering, the crease split and the completion, the owner image names for every
// pixel the candidate holding it, and -1 for the pixels of none. FEC leaves it empty.
TEST(BroccoliSteps, OwnerImageFollowsTheCandidates) {
  const auto model = general_model();
  ByHand steps(config_for_model(*model, {}, "general").detector, model);
  for (const RgbdFrame& frame : broccoli_steps_test::frames()) {
    steps.process(frame);
    std::vector<int> owner(steps.s.cloud.size(), -1);
    const auto candidates = steps.s.candidates.active();
    for (std::size_t k = 0; k < candidates.size(); ++k)
      for (int i : candidates[k].segment.indices) owner[std::size_t(i)] = int(k);
    EXPECT_EQ(steps.s.owners, owner) << "frame " << frame.index;
  }
  OutlierStageConfig no_outlier_removal;
  no_outlier_removal.enabled = false;
  steps::ClusteringStep fec(Variant::fec, {}, {}, no_outlier_removal);
  OrganizedCloud plane(8, 8);  // FEC of a whole frame takes seconds; a small plane shows the same
  for (std::size_t i = 0; i < plane.size(); ++i) plane.x[i] = 0.001f * float(i % 8), plane.y[i] = 0.001f * float(i / 8);
  std::fill(plane.z.begin(), plane.z.end(), 1.0f);
  std::vector<int> owners(plane.size(), 7);
  StageTimer timer;
  fec.run(plane, {}, {}, owners, timer);
  EXPECT_TRUE(owners.empty());
}

TEST(BroccoliSteps, CandidatePoolReusesItsSlots) {
  CandidatePool pool;
  pool.reset(2);
  pool[0].features.assign(100, 1.0f);
  pool[1].segment.indices = {4, 5};
  const float* buffer = pool[0].features.data();
  pool.reset(1);
  EXPECT_EQ(pool.size(), 1u);
  pool.reset(2);
  EXPECT_EQ(pool[0].features.data(), buffer) << "a slot keeps its buffers";
  Candidate& extra = pool.append();
  extra.segment.indices = {9};
  EXPECT_EQ(pool.size(), 3u);
  pool.remove(0);  // the last candidate takes its slot
  ASSERT_EQ(pool.size(), 2u);
  EXPECT_EQ(pool[0].segment.indices, std::vector<int>{9});
  EXPECT_EQ(pool[1].segment.indices, (std::vector<int>{4, 5}));
}
