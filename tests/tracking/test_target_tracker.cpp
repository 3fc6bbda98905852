// The target tracker's state machine on scripted detections: selection of the nearest ripe
// potato, a miss carried by a (scripted) visual tracker, reappearance, a nearer potato appearing,
// a root crossing the target (the detection splits), loss after tracking_limit frames, reselection.
#include <gtest/gtest.h>

#include <deque>

#include "cropsight/core/error.hpp"
#include "cropsight/tracking/target_tracker.hpp"

using namespace cropsight;
using namespace cropsight::tracking;

namespace {

Detection2D box_at(float cu, float cv, float half = 30) {
  Detection2D d;
  d.x1 = cu - half, d.x2 = cu + half, d.y1 = cv - half, d.y2 = cv + half;
  d.score = 0.9f;
  return d;
}

TargetCandidate cand(float cu, float cv, float dist, bool ripe = true) { return {box_at(cu, cv), dist, ripe, true}; }

// Follows the box it was started on, shifted by `drift` px per update; fails after `fail_after` updates.
class ScriptedTracker final : public VisualTracker {
 public:
  ScriptedTracker(int* inits, int fail_after = 1000) : inits_(inits), fail_after_(fail_after) {}
  void init(const ColorImage&, const Detection2D& box) override {
    box_ = box;
    updates_ = 0;
    ++*inits_;
  }
  std::optional<Detection2D> update(const ColorImage&) override {
    if (++updates_ > fail_after_) return std::nullopt;
    box_.x1 += 2, box_.x2 += 2;
    return box_;
  }

 private:
  Detection2D box_;
  int* inits_;
  int fail_after_, updates_ = 0;
};

struct TargetTrackerTest : ::testing::Test {
  ColorImage image{64, 48};
  int inits = 0;
  TargetTracker make(TargetTrackerConfig cfg = {}, int fail_after = 1000) {
    return TargetTracker(cfg, std::make_unique<ScriptedTracker>(&inits, fail_after));
  }
};

}  // namespace

TEST_F(TargetTrackerTest, SelectsTheNearestRipePotato) {
  TargetTracker t = make();
  EXPECT_EQ(t.update(&image, {}).state, TargetState::selecting);
  // Nearest (0.30 m) is unripe; the one without depth is skipped; 0.40 m beats 0.45 m.
  std::vector<TargetCandidate> c = {cand(100, 100, 0.45f), cand(300, 200, 0.30f, false), cand(200, 150, 0.40f),
                                    cand(50, 50, 0.1f)};
  c[3].depth_ok = false;
  const TargetUpdate u = t.update(&image, c);
  EXPECT_EQ(u.state, TargetState::detected);
  EXPECT_EQ(u.candidate, 2);
  EXPECT_EQ(u.target_id, 1);
  EXPECT_EQ(inits, 0);  // the visual tracker starts only when a miss needs it
}

TEST_F(TargetTrackerTest, MissIsTrackedThenReappears) {
  TargetTracker t = make();
  t.update(&image, {cand(200, 150, 0.4f)});
  const TargetUpdate miss = t.update(&image, {});
  EXPECT_EQ(miss.state, TargetState::tracked);
  EXPECT_EQ(miss.target_id, 1);
  ASSERT_TRUE(miss.box);
  EXPECT_FLOAT_EQ(miss.box->centre_x(), 202);  // the scripted tracker moved it
  EXPECT_EQ(miss.frames_tracked, 1);
  EXPECT_EQ(inits, 1);
  const TargetUpdate back = t.update(&image, {cand(205, 152, 0.39f)});
  EXPECT_EQ(back.state, TargetState::detected);
  EXPECT_EQ(back.target_id, 1);  // same target
  EXPECT_EQ(back.frames_tracked, 0);
}

TEST_F(TargetTrackerTest, LostAfterTrackingLimitThenReselects) {
  TargetTrackerConfig cfg;
  cfg.tracking_limit = 10;
  TargetTracker t = make(cfg);
  t.update(&image, {cand(200, 150, 0.4f)});
  for (int i = 1; i <= 10; ++i) {
    const TargetUpdate u = t.update(&image, {});
    ASSERT_EQ(u.state, TargetState::tracked) << i;
    EXPECT_EQ(u.frames_tracked, i);
  }
  const TargetUpdate lost = t.update(&image, {});
  EXPECT_EQ(lost.state, TargetState::lost);
  EXPECT_EQ(lost.target_id, 1);
  EXPECT_FALSE(lost.has_target());
  EXPECT_EQ(t.update(&image, {}).state, TargetState::selecting);
  const TargetUpdate next = t.update(&image, {cand(400, 300, 0.5f)});
  EXPECT_EQ(next.state, TargetState::detected);
  EXPECT_EQ(next.target_id, 2);  // a new target
}

TEST_F(TargetTrackerTest, TrackerFailureLosesTheTarget) {
  TargetTracker t = make({}, 2);
  t.update(&image, {cand(200, 150, 0.4f)});
  EXPECT_EQ(t.update(&image, {}).state, TargetState::tracked);
  EXPECT_EQ(t.update(&image, {}).state, TargetState::tracked);
  EXPECT_EQ(t.update(&image, {}).state, TargetState::lost);
  TargetTracker no_image = make();
  no_image.update(nullptr, {cand(200, 150, 0.4f)});
  EXPECT_EQ(no_image.update(nullptr, {}).state, TargetState::lost);  // nothing to track on
}

TEST_F(TargetTrackerTest, FarDetectionsDoNotContinueTheTarget) {
  TargetTrackerConfig cfg;
  cfg.epsilon_px = 50;
  TargetTracker t = make(cfg);
  t.update(&image, {cand(200, 150, 0.4f)});
  // Another potato 60 px away in u (|du| >= epsilon): the target is tracked, not switched.
  const TargetUpdate u = t.update(&image, {cand(260, 150, 0.3f)});
  EXPECT_EQ(u.state, TargetState::tracked);
  EXPECT_EQ(u.candidate, -1);
  // Per-axis rule: 49 px in u and 49 px in v is within (a Euclidean 69 px); the paper has no box gate.
  cfg.min_overlap = 0;
  cfg.max_area_ratio = 0;
  TargetTracker t2 = make(cfg);
  t2.update(&image, {cand(200, 150, 0.4f)});
  EXPECT_EQ(t2.update(&image, {cand(249, 199, 0.4f)}).state, TargetState::detected);
}

TEST_F(TargetTrackerTest, NearerPotatoWithinEpsilon) {
  // Paper association: the nearest detection within epsilon wins, even a new, nearer potato.
  TargetTrackerConfig paper;
  paper.association = TargetAssociation::nearest;
  paper.min_overlap = 0;
  paper.max_area_ratio = 0;
  TargetTracker p = make(paper);
  p.update(&image, {cand(200, 150, 0.4f)});
  const TargetUpdate pu = p.update(&image, {cand(202, 150, 0.4f), cand(320, 220, 0.3f)});
  EXPECT_EQ(pu.candidate, 1);  // the paper's rule switches to the nearer potato
  EXPECT_EQ(pu.target_id, 1);  // ... under the same id: the switch the evaluator counts
  // Ours: the detection closest to the last target centre continues it.
  TargetTracker ours = make();
  ours.update(&image, {cand(200, 150, 0.4f)});
  EXPECT_EQ(ours.update(&image, {cand(320, 220, 0.3f), cand(202, 150, 0.4f)}).candidate, 1);
}

TEST_F(TargetTrackerTest, NeighbourDoesNotTakeOverWhileTheTargetIsMissing) {
  // The target (60 x 60 px at u = 200) and a nearer neighbour 90 px to its right, well within the
  // paper's 300 px. The target's box is missing for two frames.
  TargetTrackerConfig paper;
  paper.min_overlap = 0;
  paper.max_area_ratio = 0;
  TargetTracker p = make(paper);
  p.update(&image, {cand(200, 150, 0.4f), cand(290, 150, 0.45f)});
  const TargetUpdate pu = p.update(&image, {cand(290, 150, 0.45f)});
  EXPECT_EQ(pu.candidate, 0);  // the paper's rule: the neighbour continues target 1 (a switch)
  EXPECT_EQ(pu.state, TargetState::detected);

  TargetTracker ours = make();
  ours.update(&image, {cand(200, 150, 0.4f), cand(290, 150, 0.45f)});
  for (int f = 1; f <= 2; ++f) {
    const TargetUpdate u = ours.update(&image, {cand(290, 150, 0.45f)});
    EXPECT_EQ(u.state, TargetState::tracked) << f;  // the visual tracker carries the target
    EXPECT_EQ(u.candidate, -1);
  }
  // Back (the scripted tracker drifted 4 px): detected again, same id.
  const TargetUpdate back = ours.update(&image, {cand(290, 150, 0.45f), cand(203, 151, 0.4f)});
  EXPECT_EQ(back.state, TargetState::detected);
  EXPECT_EQ(back.candidate, 1);
  EXPECT_EQ(back.target_id, 1);
  // A box overlapping the target's centre but five times its area (a nearer potato in front) is not it.
  Detection2D big = box_at(210, 150, 70);
  const TargetUpdate u = ours.update(&image, {{big, 0.3f, true, true}});
  EXPECT_EQ(u.state, TargetState::tracked);
}

TEST_F(TargetTrackerTest, PredictedMotionKeepsAFastSweepingTarget) {
  // A 20 x 20 px box moving 8 px, then 12 px a frame: without prediction the 12 px step overlaps the
  // last box by 8 / 20 < min_overlap; with it the gate's box is 5 px ahead (the last motion, at most
  // a quarter of the box) and the overlap is 13 / 20.
  const auto at = [](float u) { return TargetCandidate{box_at(u, 100, 10), 0.4f, true, true}; };
  TargetTrackerConfig still;
  still.predict_motion = false;
  TargetTracker a = make(still), b = make();
  for (TargetTracker* t : {&a, &b}) {
    t->update(&image, {at(100)});
    EXPECT_EQ(t->update(&image, {at(108)}).state, TargetState::detected);
  }
  EXPECT_EQ(a.update(&image, {at(120)}).state, TargetState::tracked);
  EXPECT_EQ(b.update(&image, {at(120)}).state, TargetState::detected);
}

TEST_F(TargetTrackerTest, LostWithANeighbourInViewSelectsTheNeighbourAfterTheLimit) {
  TargetTrackerConfig cfg;
  cfg.tracking_limit = 3;
  TargetTracker t = make(cfg);
  t.update(&image, {cand(200, 150, 0.4f), cand(330, 150, 0.45f)});
  for (int f = 1; f <= 3; ++f) EXPECT_EQ(t.update(&image, {cand(330, 150, 0.45f)}).state, TargetState::tracked) << f;
  const TargetUpdate lost = t.update(&image, {cand(330, 150, 0.45f)});
  EXPECT_EQ(lost.state, TargetState::lost);
  EXPECT_EQ(lost.target_id, 1);
  const TargetUpdate next = t.update(&image, {cand(330, 150, 0.45f)});
  EXPECT_EQ(next.state, TargetState::detected);
  EXPECT_EQ(next.target_id, 2);
  EXPECT_EQ(next.candidate, 0);
}

TEST_F(TargetTrackerTest, RootCrossingTheTarget) {
  // A root splits the target's detection into two halves for three frames, then it is whole.
  TargetTracker t = make();
  t.update(&image, {cand(200, 150, 0.4f), cand(450, 150, 0.42f)});
  for (int f = 0; f < 3; ++f) {
    Detection2D left = box_at(188, 150, 18), right = box_at(218, 150, 12);
    const TargetUpdate u =
        t.update(&image, {{right, 0.4f, true, true}, {left, 0.4f, true, true}, cand(450, 150, 0.42f)});
    EXPECT_EQ(u.state, TargetState::detected);
    EXPECT_EQ(u.target_id, 1);
    EXPECT_NE(u.candidate, 2);  // never the other potato
    EXPECT_EQ(u.parts, 2);      // the two halves are one potato
    ASSERT_TRUE(u.box);
    EXPECT_FLOAT_EQ(u.box->x1, 170);
    EXPECT_FLOAT_EQ(u.box->x2, 230);
  }
  const TargetUpdate whole = t.update(&image, {cand(450, 150, 0.42f), cand(201, 150, 0.4f)});
  EXPECT_EQ(whole.candidate, 1);
  EXPECT_EQ(whole.target_id, 1);
}

TEST_F(TargetTrackerTest, ZeroTrackingLimitDropsAtTheFirstMiss) {
  TargetTrackerConfig cfg;
  cfg.tracking_limit = 0;
  TargetTracker t = make(cfg);
  t.update(&image, {cand(200, 150, 0.4f)});
  EXPECT_EQ(t.update(&image, {}).state, TargetState::lost);
  EXPECT_EQ(inits, 0);
}

TEST(TargetTrackerConfig, RangesAreChecked) {
  TargetTrackerConfig cfg;
  cfg.epsilon_px = 0;
  EXPECT_THROW(TargetTracker{cfg}, Error);
  cfg.epsilon_px = 300;
  cfg.tracking_limit = -1;
  EXPECT_THROW(TargetTracker{cfg}, Error);
}

TEST(VisualTracker, OpenCvTrackersFollowAMovingBlob) {
  // A textured square moving 3 px per frame on a grey background: each OpenCV tracker follows it.
  for (const VisualTrackerKind kind : {VisualTrackerKind::csrt, VisualTrackerKind::kcf, VisualTrackerKind::mil}) {
    auto tracker = make_visual_tracker(kind);
    ASSERT_TRUE(tracker);
    auto frame = [](int shift) {
      ColorImage im(160, 120, Rgb8{120, 120, 120});
      for (int v = 40; v < 80; ++v)
        for (int u = 40 + shift; u < 80 + shift; ++u) {
          const bool check = ((u - shift) / 5 + v / 5) % 2;
          im.at(u, v) = check ? Rgb8{200, 150, 90} : Rgb8{90, 60, 30};
        }
      return im;
    };
    Detection2D b;
    b.x1 = 40, b.y1 = 40, b.x2 = 80, b.y2 = 80;
    tracker->init(frame(0), b);
    std::optional<Detection2D> out;
    for (int f = 1; f <= 8; ++f) out = tracker->update(frame(3 * f));
    ASSERT_TRUE(out) << config_name(kind);
    EXPECT_NEAR(out->centre_x(), 60 + 24, 4) << config_name(kind);
    EXPECT_NEAR(out->centre_y(), 60, 4) << config_name(kind);
  }
  EXPECT_EQ(make_visual_tracker(VisualTrackerKind::none), nullptr);
}
