// The visual-tracker trials on a simulated approach: CSRT follows the target's true box; a
// tracker started on the wrong place is scored as off target (the score can fail); the errors.
#include <gtest/gtest.h>

#include "cropsight/core/error.hpp"
#include "cropsight/pipeline/potato/visual_tracker_eval.hpp"
#include "cropsight/sim/potato/potato_sim.hpp"
#include "testing/testing.hpp"

using namespace cropsight;
using namespace cropsight::pipeline::potato;

namespace {

pipeline::potato::TruthSequence simulated(const std::filesystem::path& dir, int frames) {
  sim::PotatoSimConfig cfg;
  cfg.width = 320;
  cfg.height = 240;
  sim::simulate_potato_sequence(cfg, 11, frames, dir / "seq", false);
  return pipeline::potato::read_truth_sequence(dir / "seq");
}

}  // namespace

TEST(VisualTrackerEval, CsrtFollowsTheTargetOfASimulatedApproach) {
  cropsight::testing::TempDir dir;
  const auto seq = simulated(dir.path(), 8);
  ASSERT_EQ(seq.colour.size(), 8u);
  ASSERT_EQ(seq.truth.size(), 8u);
  VisualTrackerTrialConfig trial;
  trial.horizon = 4;
  trial.stride = 2;
  trial.min_visible_pixels = 100;
  const VisualTrackerEvaluation e = evaluate_visual_tracker(tracking::VisualTrackerKind::csrt, {seq}, trial);
  EXPECT_GE(e.trials, 1);
  EXPECT_GT(e.updates, 0);
  EXPECT_GT(e.mean_iou, 0.6);
  EXPECT_GE(e.success_rate, 0.75);  // most updates on target (the potato turns and is partly hidden)
  EXPECT_GT(e.update_ms, 0);
}

TEST(VisualTrackerEval, ABoxOffTheTargetScoresLow) {
  cropsight::testing::TempDir dir;
  auto seq = simulated(dir.path(), 6);
  // The tracker starts on a box of background in the top-left corner, and the "truth" of the
  // later frames is in the bottom-right corner: every scored update must be off target.
  for (auto& frame : seq.truth)
    for (auto& p : frame)
      if (p.target) {
        const float w = p.box.width(), h = p.box.height();
        p.box.x1 = 2, p.box.y1 = 2, p.box.x2 = 2 + w * 0.5f, p.box.y2 = 2 + h * 0.5f;
      }
  for (std::size_t f = 1; f < seq.truth.size(); ++f)
    for (auto& p : seq.truth[f])
      if (p.target) {
        const float w = p.box.width(), h = p.box.height();
        p.box = {float(seq.colour[f].width) - 3 - w,
                 float(seq.colour[f].height) - 3 - h,
                 float(seq.colour[f].width) - 3,
                 float(seq.colour[f].height) - 3,
                 0,
                 1};
      }
  VisualTrackerTrialConfig trial;
  trial.horizon = 3;
  trial.stride = 100;  // one trial, from frame 0
  trial.min_visible_pixels = 100;
  const VisualTrackerEvaluation e = evaluate_visual_tracker(tracking::VisualTrackerKind::kcf, {seq}, trial);
  EXPECT_LT(e.mean_iou, 0.1);
  EXPECT_LT(e.success_rate, 0.1);
}

TEST(VisualTrackerEval, NoneAndNoStartAreErrors) {
  cropsight::testing::TempDir dir;
  auto seq = simulated(dir.path(), 2);
  EXPECT_THROW(evaluate_visual_tracker(tracking::VisualTrackerKind::none, {seq}), Error);
  VisualTrackerTrialConfig trial;
  trial.min_visible_pixels = 100000000;  // no frame qualifies
  EXPECT_THROW(evaluate_visual_tracker(tracking::VisualTrackerKind::csrt, {seq}, trial), Error);
}

TEST(VisualTrackerEval, ASequenceWithoutColourIsAnErrorNamingTheFolder) {
  cropsight::testing::TempDir dir;
  sim::PotatoSimConfig cfg;
  cfg.width = 160;
  cfg.height = 120;
  sim::simulate_potato_sequence(cfg, 11, 1, dir / "seq", false);
  std::filesystem::remove_all(dir / "seq" / "color");
  try {
    pipeline::potato::read_truth_sequence(dir / "seq");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("color"), std::string::npos) << e.what();
  }
}

TEST(VisualTrackerEval, ATooSmallCsrtTemplateIsRefused) {
  tracking::CsrtParams p;
  p.template_size = 8;
  EXPECT_THROW(tracking::make_visual_tracker(tracking::VisualTrackerKind::csrt, p), Error);
}
