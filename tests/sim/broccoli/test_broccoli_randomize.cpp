// Randomised broccoli fields: reproducible from the seed, every drawn value within its
// configured range, ground truth exact (labels on the heads they name, tilted camera included).
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "cropsight/core/error.hpp"
#include "cropsight/io/config_yaml.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/sim/broccoli/broccoli_randomize.hpp"
#include "cropsight/sim/broccoli/broccoli_sim.hpp"
#include "cropsight/sim/renderer.hpp"
#include "pipeline/broccoli/broccoli_sim_frames.hpp"
#include "testing/testing.hpp"

using namespace cropsight;

namespace {
sim::BroccoliSimConfig rand_preset(const std::string& name) { return testdata::sim_preset(name); }

bool in_range(double x, const std::vector<double>& r) { return x >= r[0] - 1e-9 && x <= r[1] + 1e-9; }
}  // namespace

TEST(BroccoliRandomize, OffLeavesThePresetAsIs) {
  const sim::BroccoliSimConfig uk = rand_preset("uk");
  const sim::BroccoliSimConfig drawn = sim::draw_randomized_config(uk, 9);
  EXPECT_EQ(dump_config(drawn), dump_config(uk));
}

TEST(BroccoliRandomize, SameSeedGivesIdenticalFiles) {
  cropsight::testing::TempDir tmp;
  const sim::BroccoliSimConfig cfg = rand_preset("random");
  sim::simulate_broccoli_sequence(cfg, 41, 2, tmp / "a", false);
  sim::simulate_broccoli_sequence(cfg, 41, 2, tmp / "b", false);
  for (const char* f :
       {"camera.yaml", "poses.csv", "groundtruth.json", "depth/000001.png", "color/000001.png", "labels/000001.png"})
    EXPECT_EQ(io::read_file(tmp / "a" / f), io::read_file(tmp / "b" / f)) << f;
  EXPECT_EQ(dump_config(sim::draw_randomized_config(cfg, 41)), dump_config(sim::draw_randomized_config(cfg, 41)));
  EXPECT_NE(dump_config(sim::draw_randomized_config(cfg, 41)), dump_config(sim::draw_randomized_config(cfg, 42)));
}

// Every drawn value lies in its range, for the training and the wide preset; over 300 seeds
// every leaf family, both sensors, both row counts and sunlight occur.
TEST(BroccoliRandomize, EveryRangeIsRespected) {
  for (const char* name : {"random", "random-wide"}) {
    SCOPED_TRACE(name);
    const sim::BroccoliSimConfig base = rand_preset(name);
    const sim::SimRandomizeConfig& R = base.randomize;
    std::set<int> families, rows;
    std::set<std::string> sensors;
    int sun = 0;
    for (std::uint64_t seed = 1; seed <= 300; ++seed) {
      sim::LeafFamily fam{};
      const sim::BroccoliSimConfig c = sim::draw_randomized_config(base, seed, &fam);
      ASSERT_NO_THROW(c.validate("draw"));
      families.insert(int(fam));
      rows.insert(c.field.rows_under_camera);
      sensors.insert(c.sensor.model);
      sun += c.sensor.sunlight;
      EXPECT_TRUE(in_range(c.camera.height_m, R.camera_height_m));
      EXPECT_TRUE(in_range(c.camera.tilt_deg, R.camera_tilt_deg));
      EXPECT_TRUE(in_range(c.field.row_spacing_m, R.row_spacing_m));
      EXPECT_TRUE(in_range(c.field.in_row_spacing_m, R.in_row_spacing_m));
      EXPECT_TRUE(in_range(c.field.weed_density_m2, R.weed_density_m2));
      EXPECT_TRUE(in_range(c.plant.leaf_count_min, R.leaf_count) && in_range(c.plant.leaf_count_max, R.leaf_count));
      EXPECT_LE(c.plant.leaf_count_min, c.plant.leaf_count_max);
      EXPECT_TRUE(in_range(c.plant.leaf_length_min_m, R.leaf_length_m) &&
                  in_range(c.plant.leaf_length_max_m, R.leaf_length_m));
      EXPECT_TRUE(in_range(c.plant.leaf_elevation_min_deg, R.leaf_elevation_deg) &&
                  in_range(c.plant.leaf_elevation_max_deg, R.leaf_elevation_deg));
      EXPECT_TRUE(in_range(c.plant.leaf_droop_min_deg, R.leaf_droop_deg) &&
                  in_range(c.plant.leaf_droop_max_deg, R.leaf_droop_deg));
      EXPECT_TRUE(in_range(c.plant.leaf_ruffle_m, R.leaf_ruffle_m));
      EXPECT_TRUE(in_range(c.plant.plant_height_m, R.plant_height_m));
      EXPECT_TRUE(in_range(c.plant.inner_leaves_min, R.inner_leaves) &&
                  in_range(c.plant.inner_leaves_max, R.inner_leaves));
      EXPECT_TRUE(in_range(c.head.diameter_min_mm, R.head_diameter_mm));
      EXPECT_LE(c.head.diameter_max_mm, std::max(R.head_diameter_mm[1], c.head.diameter_min_mm + 1.0) + 1e-9);
      EXPECT_TRUE(in_range(c.head.dome_ratio_min, R.head_dome_ratio) &&
                  in_range(c.head.dome_ratio_max, R.head_dome_ratio));
      EXPECT_TRUE(in_range(c.head.floret_ratio, R.floret_ratio));
      EXPECT_TRUE(in_range(c.head.floret_height, R.floret_height));
      EXPECT_TRUE(in_range(c.plant.plant_height_m - c.plant.head_top_max_m, R.head_below_canopy_m));
      EXPECT_TRUE(in_range(c.soil.roughness_m, R.soil_roughness_m));
      EXPECT_TRUE(in_range(c.soil.clod_density_m2, R.clod_density_m2));
      EXPECT_TRUE(in_range(c.sensor.noise_at_1m_m, R.tof_noise_at_1m_m));
      EXPECT_TRUE(in_range(c.sensor.flying_prob, R.tof_flying_prob));
      EXPECT_LE(c.sensor.flying_prob + c.sensor.edge_dropout_prob, 1.0);
      EXPECT_TRUE(in_range(c.sensor.amplitude_min, R.tof_amplitude_min));
      EXPECT_TRUE(in_range(c.sensor.random_dropout, R.random_dropout));
      EXPECT_TRUE(in_range(c.sensor.stereo_noise_at_1m_m, R.stereo_noise_at_1m_m));
      EXPECT_TRUE(in_range(c.sensor.stereo_hole_fraction, R.stereo_hole_fraction));
    }
    EXPECT_EQ(families.size(), 3u);
    EXPECT_EQ(rows, (std::set<int>{1, 2}));
    EXPECT_EQ(sensors, (std::set<std::string>{"stereo", "tof"}));
    EXPECT_GT(sun, 0);
  }
}

TEST(BroccoliRandomize, MalformedRangeIsAnError) {
  sim::BroccoliSimConfig c = rand_preset("random");
  c.randomize.camera_height_m = {1.5, 1.1};
  EXPECT_THROW(c.validate("cfg"), Error);
  c = rand_preset("random");
  c.randomize.leaf_family_weights = {0, 0, 0};
  EXPECT_THROW(c.validate("cfg"), Error);
  c = rand_preset("random");
  c.sensor.model = "lidar";
  EXPECT_THROW(c.validate("cfg"), Error);
}

// Labels stay exact on randomised scenes: a labelled pixel with depth deprojects (with the drawn
// tilt) to within a head diameter of its head's apex; sequences with a stereo sensor lose about
// their hole fraction.
TEST(BroccoliRandomize, GroundTruthStaysConsistent) {
  const sim::BroccoliSimConfig base = rand_preset("random-wide");
  int stereo_seen = 0, tilted_seen = 0;
  for (std::uint64_t seed : {3, 4, 5, 6}) {
    sim::BroccoliSimulator s(base, seed, 3);
    const auto& cfg = s.config();
    SCOPED_TRACE("seed " + std::to_string(seed) + " sensor " + cfg.sensor.model);
    stereo_seen += cfg.sensor.model == "stereo";
    tilted_seen += cfg.camera.tilt_deg > 0.5;
    const Eigen::Matrix3d Rt =
        sim::tilted_camera_rotation(cfg.camera.tilt_deg, cfg.camera.tilt_azimuth_deg).transpose();
    std::vector<RgbdFrame> frames;
    for (int i = 0; i < s.frames(); ++i) frames.push_back(s.render(i));
    const io::GroundTruth gt = s.groundtruth();
    EXPECT_EQ(gt.attributes.at("randomized"), "1");
    std::map<int, const io::InstanceTruth*> by_id;
    for (const auto& t : gt.instances) {
      by_id[t.id] = &t;
      EXPECT_GE(t.diameter_mm, cfg.head.diameter_min_mm * 0.9);
      EXPECT_LE(t.diameter_mm, cfg.head.diameter_max_mm * 1.1);
    }
    long labelled = 0, far = 0;
    for (const auto& f : frames)
      for (int v = 0; v < f.labels.height; ++v)
        for (int u = 0; u < f.labels.width; ++u) {
          const int id = f.labels.at(u, v);
          const std::uint16_t d = f.depth.at(u, v);
          if (!id || d == 0) continue;
          ++labelled;
          ASSERT_TRUE(by_id.count(id));
          const Eigen::Vector3d p =
              *f.camera_position +
              Rt * f.camera.deproject(float(u), float(v), float(d * f.camera.depth_scale)).cast<double>();
          if ((p - by_id[id]->position).norm() > by_id[id]->diameter_mm / 1000.0) ++far;
        }
    if (labelled > 0) {
      EXPECT_LT(double(far) / double(labelled), 0.02);
    }
  }
  EXPECT_GT(tilted_seen, 0);
}
