// Simulator invariants: determinism, ground-truth consistency, motion, sensor noise model.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>

#include "cropsight/core/error.hpp"
#include "cropsight/io/config_yaml.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/sim/broccoli/broccoli_sim.hpp"
#include "cropsight/sim/tof_sensor.hpp"
#include "pipeline/broccoli/broccoli_sim_frames.hpp"
#include "testing/testing.hpp"

using namespace cropsight;

namespace {
// The shipped presets (configs/sim-broccoli-<variety>.yaml), as `simulate broccoli --variety`
// applies them.
sim::BroccoliSimConfig preset(const std::string& variety) { return testdata::sim_preset(variety); }
sim::BroccoliSimConfig spain() { return preset("spain"); }

// Camera frame -> field frame for the downward-looking camera (broccoli_sim.hpp):
// field x = camera y, field y = camera x, field z = -camera z, plus the camera position.
Eigen::Vector3d to_field(const Eigen::Vector3f& p, const Eigen::Vector3d& cam) {
  return cam + Eigen::Vector3d(p.y(), p.x(), -p.z());
}
}  // namespace

TEST(BroccoliSim, SameSeedGivesIdenticalFramesAndFiles) {
  cropsight::testing::TempDir tmp;
  sim::BroccoliSimConfig cfg;
  sim::simulate_broccoli_sequence(cfg, 5, 2, tmp / "a", false);
  sim::simulate_broccoli_sequence(cfg, 5, 2, tmp / "b", false);
  for (const char* f :
       {"camera.yaml", "poses.csv", "groundtruth.json", "depth/000001.png", "color/000001.png", "labels/000001.png"})
    EXPECT_EQ(io::read_file(tmp / "a" / f), io::read_file(tmp / "b" / f)) << f;
  sim::simulate_broccoli_sequence(cfg, 6, 2, tmp / "c", false);
  EXPECT_NE(io::read_file(tmp / "a" / "depth/000001.png"), io::read_file(tmp / "c" / "depth/000001.png"));
}

TEST(BroccoliSim, RefusesToOverwriteWithoutForce) {
  cropsight::testing::TempDir tmp;
  sim::BroccoliSimConfig cfg;
  sim::simulate_broccoli_sequence(cfg, 5, 1, tmp / "a", false);
  EXPECT_THROW(sim::simulate_broccoli_sequence(cfg, 5, 1, tmp / "a", false), Error);
  EXPECT_NO_THROW(sim::simulate_broccoli_sequence(cfg, 5, 1, tmp / "a", true));
}

TEST(BroccoliSim, InvalidConfigIsAnError) {
  sim::BroccoliSimConfig cfg;
  cfg.motion.fps = -1;
  EXPECT_THROW(cfg.validate("cfg"), Error);
  EXPECT_THROW(sim::BroccoliSimulator(sim::BroccoliSimConfig{}, 1, 0), Error);
}

// A head's labelled pixels deproject to field points within its diameter of its recorded
// position; diameters stay within the preset's range; labels sit on valid depth.
TEST(BroccoliSim, GroundTruthIsConsistent) {
  for (const auto& cfg : {sim::BroccoliSimConfig{}, spain()}) {
    SCOPED_TRACE(cfg.field.variety);
    sim::BroccoliSimulator s(cfg, 3, 6);
    std::vector<RgbdFrame> frames;
    for (int i = 0; i < s.frames(); ++i) frames.push_back(s.render(i));
    const io::GroundTruth gt = s.groundtruth();
    ASSERT_FALSE(gt.instances.empty());
    std::map<int, const io::InstanceTruth*> by_id;
    for (const auto& t : gt.instances) {
      by_id[t.id] = &t;
      EXPECT_GE(t.diameter_mm, cfg.head.diameter_min_mm - 1e-6);
      EXPECT_LE(t.diameter_mm, cfg.head.diameter_max_mm + 1e-6);
    }
    long labelled = 0, far = 0;
    for (const auto& f : frames) {
      ASSERT_TRUE(f.camera_position.has_value());
      for (int v = 0; v < f.labels.height; ++v)
        for (int u = 0; u < f.labels.width; ++u) {
          const int id = f.labels.at(u, v);
          if (!id) continue;
          ++labelled;
          ASSERT_TRUE(by_id.count(id)) << "label " << id << " has no ground-truth instance";
          const std::uint16_t d = f.depth.at(u, v);
          if (d == 0) continue;  // labelled but no return (dropout): allowed, counted below
          const Eigen::Vector3d p =
              to_field(f.camera.deproject(float(u), float(v), float(d * f.camera.depth_scale)), *f.camera_position);
          const auto& t = *by_id[id];
          if ((p - t.position).norm() > t.diameter_mm / 1000.0) ++far;
        }
    }
    EXPECT_GT(labelled, 1000);
    // Sensor noise and flying pixels may push a handful of points out; the geometry must not.
    EXPECT_LT(double(far) / double(labelled), 0.01);
  }
}

// Occlusion lies in [0, 1] per head, and the spain preset's larger canopy (longer outer leaves,
// more and longer inner leaves) hides the heads more than uk's, as the issue describes
// (docs/simulator.md measures both over more seeds and frames).
TEST(BroccoliSim, OcclusionWithinRange) {
  auto mean_occlusion = [](const sim::BroccoliSimConfig& cfg) {
    sim::BroccoliSimulator s(cfg, 11, 12);
    for (int i = 0; i < s.frames(); ++i) s.render(i);
    double sum = 0;
    int n = 0;
    for (const auto& t : s.groundtruth().instances) {
      const double o = t.extra.at("occlusion");
      if (o < 0) continue;  // never fully in view
      EXPECT_GE(o, 0.0);
      EXPECT_LE(o, 1.0);
      sum += o;
      ++n;
    }
    EXPECT_GT(n, 0);
    return n ? sum / n : 0.0;
  };
  const double uk = mean_occlusion(sim::BroccoliSimConfig{});
  const double es = mean_occlusion(spain());
  EXPECT_GT(uk, 0.02) << "leaves must partly hide the heads";
  EXPECT_LT(uk, 0.8);
  EXPECT_GT(es, 0.02);
  EXPECT_LT(es, 0.9);
  EXPECT_GT(es, uk) << "spain's larger canopy must hide the heads more than uk's";
  std::printf("mean occlusion: uk %.3f spain %.3f\n", uk, es);
}

TEST(BroccoliSim, CameraAdvancesAtSpeedOverFps) {
  sim::BroccoliSimConfig cfg;
  sim::BroccoliSimulator s(cfg, 2, 40);
  const double expected = cfg.motion.speed_mps / cfg.motion.fps;
  const double mean_step = (s.camera_position(39).x() - s.camera_position(0).x()) / 39.0;
  EXPECT_NEAR(mean_step, expected, 0.1 * expected);
  for (int i = 1; i < 40; ++i) {
    EXPECT_GT(s.camera_position(i).x(), s.camera_position(i - 1).x());
    EXPECT_NEAR(s.camera_position(i).z(), cfg.camera.height_m, 0.03);
    EXPECT_DOUBLE_EQ(s.timestamp(i), i / cfg.motion.fps);
  }
}

TEST(BroccoliSim, DepthNoiseGrowsWithRangeAndDarkness) {
  sim::SimSensorConfig cfg;
  EXPECT_NEAR(sim::tof_noise_sigma(cfg, 1.0, cfg.reference_reflectivity), cfg.noise_at_1m_m, 0.5 * cfg.noise_at_1m_m);
  EXPECT_LT(sim::tof_noise_sigma(cfg, 0.8, 0.5), sim::tof_noise_sigma(cfg, 1.3, 0.5));
  EXPECT_LT(sim::tof_noise_sigma(cfg, 1.0, 0.6), sim::tof_noise_sigma(cfg, 1.0, 0.1));
  sim::SimSensorConfig sun = cfg;
  sun.sunlight = true;
  EXPECT_LT(sim::tof_noise_sigma(cfg, 1.0, 0.5), sim::tof_noise_sigma(sun, 1.0, 0.5));
}

TEST(BroccoliSim, FramesHaveKinectGeometryAndValidDepth) {
  sim::BroccoliSimulator s(sim::BroccoliSimConfig{}, 4, 1);
  const RgbdFrame f = s.render(0);
  EXPECT_EQ(f.depth.width, 512);
  EXPECT_EQ(f.depth.height, 424);
  EXPECT_EQ(f.color.width, 512);
  EXPECT_NEAR(2 * std::atan(0.5 * 512 / f.camera.fx) * 180 / M_PI, 70.6, 0.1);
  long valid = 0, holes = 0;
  for (auto d : f.depth.data) (d ? valid : holes)++;
  EXPECT_GT(valid, long(0.8 * f.depth.size()));
  EXPECT_GT(holes, 0) << "ToF frames have missing returns";
}

// Heads stand on a depth step over the leaves next to them (plant.leaf_rim_step_*): with a
// noise-free sensor, the pixels bordering a head's labelled region are mostly farther than the
// head's edge pixel by more than 1 cm, while leaves made to meet the head's outline at the rim's
// height (every leaf touching, no clearance) give continuous head-leaf borders.
TEST(BroccoliSim, HeadRimsStandAboveTheLeavesNextToThem) {
  auto continuous_share = [](bool touching) {
    sim::BroccoliSimConfig cfg;
    if (touching) cfg.plant.leaf_rim_touch_prob = 1.0, cfg.plant.leaf_rim_clearance_m = 0.0;
    cfg.plant.inner_leaves_min = cfg.plant.inner_leaves_max = 0;  // they cover rims from above
    cfg.sensor.noise_at_1m_m = 0;
    cfg.sensor.flying_prob = cfg.sensor.edge_dropout_prob = 0;
    cfg.sensor.random_dropout = 0;
    sim::BroccoliSimulator s(cfg, 8, 1);
    long border = 0, continuous = 0;
    for (int i = 0; i < s.frames(); ++i) {
      const RgbdFrame f = s.render(i);
      for (int v = 1; v + 1 < f.depth.height; ++v)
        for (int u = 1; u + 1 < f.depth.width; ++u) {
          const int id = f.labels.at(u, v);
          const std::uint16_t d = f.depth.at(u, v);
          if (!id || !d) continue;
          for (auto [du, dv] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
            const std::uint16_t dn = f.depth.at(u + du, v + dv);
            if (f.labels.at(u + du, v + dv) == id || !dn) continue;
            ++border;
            continuous += std::abs(int(dn) - int(d)) * f.camera.depth_scale < 0.01;
          }
        }
    }
    EXPECT_GT(border, 300);
    return double(continuous) / double(std::max(1L, border));
  };
  const double stepped = continuous_share(false);  // the preset
  const double touching = continuous_share(true);
  std::printf("head border pixels with a neighbour within 1 cm: preset %.3f, all leaves touching %.3f\n", stepped,
              touching);
  EXPECT_LT(stepped, 0.05);
  EXPECT_GT(touching, stepped + 0.1);
}
