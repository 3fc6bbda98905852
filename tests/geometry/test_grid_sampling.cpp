#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "cropsight/core/error.hpp"
#include "cropsight/geometry/grid_sampling.hpp"

using namespace cropsight::geometry;

namespace {
// A dense blob (like a seedling) on a sparse plane (the soil), plus a few NaN points.
std::vector<Eigen::Vector3f> scene(int n_plane, int n_blob) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-0.5f, 0.5f);
  std::normal_distribution<float> g(0, 0.02f);
  std::vector<Eigen::Vector3f> pts;
  for (int i = 0; i < n_plane; ++i) pts.emplace_back(u(rng), u(rng), 0.7f);
  for (int i = 0; i < n_blob; ++i) pts.emplace_back(g(rng), g(rng), 0.6f + g(rng));
  for (int i = 0; i < 10; ++i) pts.emplace_back(std::nanf(""), 0.f, 0.f);
  return pts;
}
}  // namespace

TEST(GridSampling, ExactCountWithinBoundsNoDuplicates) {
  const auto pts = scene(60000, 40000);
  GridSamplingConfig cfg;
  const auto idx = sample_exact(pts, cfg);
  ASSERT_EQ(int(idx.size()), 4096);
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(1e9f), hi = -lo;
  for (const auto& p : pts)
    if (p.allFinite()) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  std::set<int> uniq(idx.begin(), idx.end());
  EXPECT_EQ(uniq.size(), idx.size());
  for (int i : idx) {
    ASSERT_TRUE(i >= 0 && i < int(pts.size()));
    ASSERT_TRUE(pts[i].allFinite());
    EXPECT_TRUE((pts[i].array() >= lo.array()).all() && (pts[i].array() <= hi.array()).all());
  }
}

TEST(GridSampling, RepresentativesRespectBoxLimitAndAreNonUniform) {
  const auto pts = scene(20000, 20000);
  const auto reps = nonuniform_grid_representatives(pts, 10, 1e-4);
  // At least N / 10 boxes; each representative is a real point; no point twice.
  EXPECT_GE(int(reps.size()), 40000 / 10);
  EXPECT_EQ(std::set<int>(reps.begin(), reps.end()).size(), reps.size());
  // Non-uniform: the dense blob (half of the points in a tiny volume) keeps a large share.
  int blob = 0;
  for (int i : reps) blob += i >= 20000;
  EXPECT_GT(double(blob) / double(reps.size()), 0.25);
}

TEST(GridSampling, SmallCloudIsPaddedToTheExactCount) {
  const auto pts = scene(100, 0);
  GridSamplingConfig cfg;
  cfg.target_points = 256;
  const auto idx = sample_exact(pts, cfg);
  ASSERT_EQ(idx.size(), 256u);
  for (int i : idx) EXPECT_TRUE(pts[i].allFinite());
}

TEST(GridSampling, DeterministicAndRejectsBadInput) {
  const auto pts = scene(10000, 5000);
  GridSamplingConfig cfg;
  cfg.target_points = 1000;
  EXPECT_EQ(sample_exact(pts, cfg), sample_exact(pts, cfg));
  std::vector<Eigen::Vector3f> none(5, Eigen::Vector3f::Constant(std::nanf("")));
  EXPECT_THROW(sample_exact(none, cfg), cropsight::Error);
  EXPECT_THROW(nonuniform_grid_representatives(pts, 0, 1e-4), cropsight::Error);
}
