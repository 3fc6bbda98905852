// The potato simulator: a readable sequence with depth_color/, reproducible from the seed, truth
// that agrees with the rendered depth and labels, and no depth below the minimum range.
#include <gtest/gtest.h>

#include <algorithm>

#include "cropsight/io/depth_colormap.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/pipeline/potato/truth.hpp"
#include "cropsight/sim/potato/potato_sim.hpp"
#include "testing/testing.hpp"

using namespace cropsight;

namespace {
sim::PotatoSimConfig small() {
  sim::PotatoSimConfig cfg;
  cfg.width = 320;
  cfg.height = 240;
  return cfg;
}
}  // namespace

TEST(PotatoSim, WritesASequenceWhoseTruthMatchesTheRendering) {
  cropsight::testing::TempDir dir;
  const auto out = dir / "seq";
  const auto s = sim::simulate_potato_sequence(small(), 5, 4, out, false);
  EXPECT_EQ(s.frames, 4);
  EXPECT_GT(s.valid_fraction, 0.5);
  io::SequenceReader reader(out);
  ASSERT_EQ(reader.size(), 4);
  EXPECT_TRUE(std::filesystem::exists(out / "depth_color" / "000003.png"));
  const auto& gt = reader.groundtruth();
  ASSERT_EQ(gt.instances.size(), 4u);
  const RgbdFrame f = reader.read(3);  // end of the approach: target at 0.3 m
  const auto truth = pipeline::potato::frame_truth(gt, *f.camera_position, f.camera, f.labels);
  const auto& t = truth[0];
  ASSERT_TRUE(t.target);
  EXPECT_NEAR(t.centre_camera.z(), 0.3, 0.01);
  ASSERT_GT(t.visible_pixels, 100);
  // The centre projects inside the visible box; the depth there is the front surface.
  const Eigen::Vector2f c = f.camera.project(t.centre_camera.cast<float>());
  EXPECT_GT(c.x() + 0.5f, t.box.x1);
  EXPECT_LT(c.x() + 0.5f, t.box.x2);
  EXPECT_GT(c.y() + 0.5f, t.box.y1);
  EXPECT_LT(c.y() + 0.5f, t.box.y2);
  const double thickness = gt.instances[0].extra.at("thickness_m");
  int near = 0, n = 0;
  for (int dv = -2; dv <= 2; ++dv)
    for (int du = -2; du <= 2; ++du) {
      const int u = int(std::lround(c.x())) + du, v = int(std::lround(c.y())) + dv;
      if (f.labels.at(u, v) != t.id || f.depth.at(u, v) == 0) continue;
      ++n;
      // Front surface between centre - half thickness - bumps and the centre.
      const double z = f.depth.at(u, v) * f.camera.depth_scale;
      near += z < t.centre_camera.z() && z > t.centre_camera.z() - 0.5 * thickness - 0.01;
    }
  EXPECT_GT(n, 5);
  EXPECT_GE(near, n - 1);
  EXPECT_GE(t.angle_rad, 0.0);
  EXPECT_LT(t.angle_rad, M_PI);
}

TEST(PotatoSim, ReproducibleFromTheSeedAndScenesDiffer) {
  cropsight::testing::TempDir dir;
  sim::simulate_potato_sequence(small(), 9, 1, dir / "a", false);
  sim::simulate_potato_sequence(small(), 9, 1, dir / "b", false);
  auto room = small();
  room.scene = sim::PotatoScene::room;
  sim::simulate_potato_sequence(room, 9, 1, dir / "c", false);
  const RgbdFrame a = io::SequenceReader(dir / "a").read(0), b = io::SequenceReader(dir / "b").read(0);
  const RgbdFrame c = io::SequenceReader(dir / "c").read(0);
  EXPECT_EQ(a.depth, b.depth);
  EXPECT_EQ(a.color, b.color);
  EXPECT_NE(a.color, c.color);
  EXPECT_THROW(sim::simulate_potato_sequence(small(), 9, 1, dir / "a", false), Error);
}

TEST(PotatoSim, RootsAcrossOthersCrossEveryPotatoAndLeaveTheRestOfTheScene) {
  cropsight::testing::TempDir dir;
  auto with = small();
  with.roots_across_others = true;
  sim::simulate_potato_sequence(small(), 9, 1, dir / "a", false);
  sim::simulate_potato_sequence(with, 9, 1, dir / "b", false);
  const io::SequenceReader ra(dir / "a"), rb(dir / "b");
  const RgbdFrame a = ra.read(0), b = rb.read(0);
  ASSERT_EQ(ra.groundtruth().instances.size(), rb.groundtruth().instances.size());
  int crossed = 0;
  for (std::size_t k = 0; k < ra.groundtruth().instances.size(); ++k) {
    const auto& ia = ra.groundtruth().instances[k];
    EXPECT_EQ(ia.position, rb.groundtruth().instances[k].position);  // the same potatoes
    const auto count = [&](const LabelImage& l) { return std::count(l.data.begin(), l.data.end(), ia.id); };
    const long before = count(a.labels), after = count(b.labels);
    if (ia.extra.at("target") > 0.5 || before < 50) continue;
    EXPECT_LT(after, before) << "potato " << ia.id << ": no root in front of it";
    ++crossed;
  }
  EXPECT_GT(crossed, 0);
}

TEST(PotatoSim, NoDepthBelowTheMinimumRange) {
  cropsight::testing::TempDir dir;
  auto cfg = small();
  cfg.scan_distance_m = 0.27;  // the potato's front comes nearer than 0.25 m
  cfg.approach_end_m = 0.27;
  cfg.root_across_target = false;
  sim::simulate_potato_sequence(cfg, 3, 1, dir / "s", false);
  const RgbdFrame f = io::SequenceReader(dir / "s").read(0);
  for (auto d : f.depth.data) {
    if (d) {
      EXPECT_GE(d * f.camera.depth_scale, 0.25 - 1e-9);
    }
  }
  EXPECT_EQ(f.depth.at(160, 120), 0);  // the target's front at the centre is too near
}

TEST(DepthColormap, NearRedFarBlueNoneBlack) {
  EXPECT_EQ(io::depth_color(0.f, 0.3f, 1.f), (Rgb8{0, 0, 0}));
  const Rgb8 near = io::depth_color(0.3f, 0.3f, 1.f), far = io::depth_color(1.f, 0.3f, 1.f);
  EXPECT_GT(near.r, 100);
  EXPECT_EQ(near.b, 0);
  EXPECT_GT(far.b, 100);
  EXPECT_EQ(far.r, 0);
}
