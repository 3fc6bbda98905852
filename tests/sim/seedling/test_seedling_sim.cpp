#include <gtest/gtest.h>

#include <cmath>

#include "cropsight/core/error.hpp"
#include "cropsight/sim/seedling/seedling_sim.hpp"

using namespace cropsight;

TEST(SeedlingSim, DeterministicWithConsistentTruth) {
  sim::SeedlingSimConfig cfg;
  cfg.width = 320;
  cfg.height = 240;
  cfg.supersample = 1;
  const auto a = sim::simulate_seedling_pair(cfg, 9, 0), b = sim::simulate_seedling_pair(cfg, 9, 0);
  EXPECT_EQ(a.left, b.left);
  EXPECT_EQ(a.right, b.right);
  EXPECT_GE(a.leaves, 4);
  EXPECT_LE(a.leaves, 6);
  EXPECT_GE(a.distance, 0.5);
  EXPECT_LE(a.distance, 0.8);
  long seedling = 0, valid = 0;
  const auto rig = cfg.rig();
  for (std::size_t i = 0; i < a.mask.size(); ++i) {
    seedling += a.mask.data[i] > 0;
    valid += std::isfinite(a.disparity.data[i]);
  }
  EXPECT_GT(seedling, 100);
  EXPECT_EQ(valid, long(a.mask.size()));  // soil everywhere below the horizon
  // The seedling base lies on the soil plane, at the working distance.
  EXPECT_NEAR(a.plane_normal.dot(a.seedling_base) + a.plane_d, 0.0, 1e-6);
  EXPECT_NEAR(a.seedling_base.norm(), a.distance, 0.06);
  // Disparity at the image centre matches the depth of the soil/plant there (f B / z > 0).
  EXPECT_GT(a.disparity.at(cfg.width / 2, cfg.height / 2), rig.f * rig.baseline() / 0.9);
  EXPECT_GT(a.envelope.height, 0.03);
  EXPECT_LT(a.envelope.height, 0.2);
  EXPECT_GT(a.envelope.length, a.envelope.height);
}

TEST(SeedlingSim, RejectsBadConfig) {
  sim::SeedlingSimConfig cfg;
  cfg.leaves_min = 0;
  EXPECT_THROW(sim::simulate_seedling_pair(cfg, 1, 0), Error);
}
