// The grape simulator: a cloud the grape readers take, normalised to the unit sphere, with every
// label of the dataset, label-0 points at one position as in the shared clouds, a truth that maps
// back to the camera frame, and the same cloud for the same seed.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "cropsight/core/error.hpp"
#include "cropsight/io/grape_text.hpp"
#include "cropsight/sim/grape/grape_sim.hpp"
#include "testing/testing.hpp"

using namespace cropsight;

TEST(GrapeSim, SameSeedSameCloudOtherSeedAnother) {
  const sim::GrapeSimConfig cfg;
  const auto a = sim::simulate_grape_cloud(cfg, 4), b = sim::simulate_grape_cloud(cfg, 4);
  const auto c = sim::simulate_grape_cloud(cfg, 5);
  ASSERT_EQ(a.cloud.size(), b.cloud.size());
  EXPECT_EQ(a.cloud.points, b.cloud.points);
  EXPECT_EQ(a.cloud.labels, b.cloud.labels);
  EXPECT_NE(a.cloud.size(), c.cloud.size());
}

TEST(GrapeSim, EveryLabelUnitSphereAndTheDatasetsLabelZeroPosition) {
  const auto s = sim::simulate_grape_cloud({}, 4);
  const Cloud& c = s.cloud;
  ASSERT_NO_THROW(c.validate("simulated grape cloud"));
  EXPECT_GT(c.size(), 10000u);  // the shared clouds hold 14k-40k points
  for (int l = 0; l < sim::kGrapeLabels; ++l) EXPECT_GT(s.truth.label_counts[std::size_t(l)], 0) << "label " << l;
  for (int l : {0, 2, 3, 4, 5}) EXPECT_GT(s.truth.label_counts[1], s.truth.label_counts[std::size_t(l)]);
  float r_max = 0;
  Eigen::Vector3f mean = Eigen::Vector3f::Zero();
  for (const auto& p : c.points) {
    r_max = std::max(r_max, p.norm());
    mean += p;
  }
  EXPECT_NEAR(r_max, 1.f, 1e-4f);
  EXPECT_LT((mean / float(c.size())).norm(), 1e-4f);
  // Pixels without a return sit at the camera centre: one position, the origin in metres.
  for (std::size_t k = 0; k < c.size(); ++k) {
    if (c.labels[k] != sim::kGrapeNoReturn) continue;
    ASSERT_LT(s.to_camera(c.points[k]).norm(), 1e-5f);
  }
  for (std::size_t k = 0; k < c.size(); ++k) ASSERT_NEAR(c.normals[k].norm(), 1.f, 1e-3f);
}

TEST(GrapeSim, TruthMapsBackToTheCameraFrame) {
  const auto s = sim::simulate_grape_cloud({}, 6);
  Eigen::Vector3f sum = Eigen::Vector3f::Zero();
  int n = 0;
  for (std::size_t k = 0; k < s.cloud.size(); ++k)
    if (s.cloud.labels[k] == sim::kGrapePeduncle) {
      sum += s.to_camera(s.cloud.points[k]);
      ++n;
    }
  ASSERT_EQ(n, s.truth.peduncle_points);
  // The truth is the noise-free centroid; the written points carry depth noise (~0.4 mm here).
  EXPECT_LT((sum / float(n) - s.truth.cut_point_m).norm(), 0.002f);
  EXPECT_NEAR(s.truth.cut_point_m.z(), s.truth.distance_m, 0.03);  // on the bunch's axis
  EXPECT_LT(s.truth.peduncle_axis.y(), -0.8f);                     // pointing up in the image
}

TEST(GrapeSim, WritesWhatTheGrapeReaderTakesAndItsTruth) {
  cropsight::testing::TempDir dir;
  const auto s = sim::simulate_grape_cloud({}, 7);
  sim::write_grape_sim(dir.path(), s);
  const Cloud back = io::read_grape_text(dir / "cloud.txt");
  EXPECT_EQ(back.labels, s.cloud.labels);
  ASSERT_EQ(back.size(), s.cloud.size());
  EXPECT_LT((back.points[10] - s.cloud.points[10]).norm(), 1e-5f);
  std::ifstream in(dir / "truth.json");
  const auto j = nlohmann::json::parse(in);
  EXPECT_NEAR(j.at("scale_m").get<double>(), s.scale, 1e-6);
  EXPECT_EQ(j.at("label_counts").at(2).get<long>(), s.truth.label_counts[2]);
  EXPECT_EQ(j.at("cut_point").at("position_m").size(), 3u);
}

TEST(GrapeSim, RefusesAConfigWhoseMinimumExceedsItsMaximum) {
  sim::GrapeSimConfig cfg;
  cfg.berries_min = 100;
  cfg.berries_max = 50;
  const std::string msg = cropsight::testing::error_message([&] { sim::simulate_grape_cloud(cfg, 1); });
  EXPECT_NE(msg.find("berries_min"), std::string::npos) << msg;
  cfg = {};
  cfg.focal_px = 10;
  EXPECT_THROW(sim::simulate_grape_cloud(cfg, 1), Error);
}
