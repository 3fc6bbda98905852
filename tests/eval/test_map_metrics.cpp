// Map and size metrics on hand-made cases.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "cropsight/core/error.hpp"
#include "cropsight/eval/map_metrics.hpp"
#include "cropsight/eval/size_metrics.hpp"

using namespace cropsight;
using namespace cropsight::eval;

namespace {
Eigen::Vector3d P(double x, double y = 0.0, double z = 0.0) { return {x, y, z}; }
}  // namespace

TEST(MapMetrics, HungarianBeatsGreedy) {
  // Truth t1 = 0, t2 = 0.078; map m1 = 0.029 (0.029 from t1, 0.049 from t2), m2 = −0.03 (0.03 from
  // t1 only). Closest-first greedy pairs m1–t1 and leaves m2 and t2 unmatched (1 pair); the
  // optimum pairs m2–t1 and m1–t2 (2 pairs).
  const auto r = map_metrics({P(0.029), P(-0.03)}, {P(0.0), P(0.078)});
  EXPECT_EQ(r.matched, 2);
  EXPECT_DOUBLE_EQ(r.precision, 1.0);
  EXPECT_DOUBLE_EQ(r.recall, 1.0);
  ASSERT_EQ(r.matches.size(), 2u);
  EXPECT_EQ(r.matches[0].truth_index, 1);
  EXPECT_EQ(r.matches[1].truth_index, 0);
  EXPECT_NEAR(r.mean_distance_m, (0.049 + 0.03) / 2, 1e-12);
}

TEST(MapMetrics, CountsDuplicatesMissesAndFalseHeads) {
  // t0 mapped twice (one duplicate), t1 mapped once, t2 missed, one map head far from any truth.
  const std::vector<Eigen::Vector3d> truth{P(0), P(0.5), P(1.0)};
  const std::vector<Eigen::Vector3d> map{P(0.01), P(-0.02), P(0.51), P(2.0)};
  const auto r = map_metrics(map, truth);
  EXPECT_EQ(r.matched, 2);
  EXPECT_EQ(r.duplicates, 1);
  EXPECT_DOUBLE_EQ(r.precision, 0.5);
  EXPECT_DOUBLE_EQ(r.recall, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(r.duplicate_rate, 0.25);
  EXPECT_EQ(r.count_error, 1);
  EXPECT_DOUBLE_EQ(r.count_error_rel, 1.0 / 3.0);
  EXPECT_EQ(r.matches[0].map_index, 0);  // the closer of the two takes t0
}

TEST(MapMetrics, GroundPlaneByDefault) {
  // 8 cm apart in height only: the same head in X–Y, two heads in 3D.
  const auto flat = map_metrics({P(0, 0, 0.18)}, {P(0, 0, 0.10)});
  EXPECT_EQ(flat.matched, 1);
  MapMatchConfig cfg;
  cfg.use_z = true;
  EXPECT_EQ(map_metrics({P(0, 0, 0.18)}, {P(0, 0, 0.10)}, cfg).matched, 0);
  const auto edge = map_metrics({P(0.0, 0.0501)}, {P(0)});
  EXPECT_EQ(edge.matched, 0);
}

TEST(MapMetrics, EmptyInputs) {
  const auto a = map_metrics({}, {P(0)});
  EXPECT_TRUE(std::isnan(a.precision));
  EXPECT_DOUBLE_EQ(a.recall, 0.0);
  EXPECT_EQ(a.count_error, -1);
  const auto b = map_metrics({P(0)}, {});
  EXPECT_DOUBLE_EQ(b.precision, 0.0);
  EXPECT_TRUE(std::isnan(b.recall));
  EXPECT_THROW(map_metrics({}, {}, MapMatchConfig{0.0, false}), Error);
}

TEST(MapMetrics, HeadsAtIgnoreRegionsAreNeitherTrueNorFalse) {
  // t0 and t1 required; s a head too little seen to be required (an ignore region). Map: t0, t1,
  // a head at s, a duplicate of t0 that is also near s, and a head far from everything.
  const std::vector<Eigen::Vector3d> truth{P(0), P(0.5)};
  const std::vector<Eigen::Vector3d> ignore{P(0.06), P(3.0)};
  const std::vector<Eigen::Vector3d> map{P(0.0), P(0.5), P(0.09), P(0.03), P(2.0)};
  const auto r = map_metrics(map, truth, {}, ignore);
  EXPECT_EQ(r.matched, 2);
  EXPECT_EQ(r.duplicates, 1);  // P(0.03) is t0's duplicate first: duplicates stay false heads
  EXPECT_EQ(r.ignored, 1);     // P(0.09): 0.03 from s, 0.09 from t0
  EXPECT_DOUBLE_EQ(r.precision, 2.0 / 5.0);
  EXPECT_DOUBLE_EQ(r.precision_visible, 2.0 / 4.0);
  EXPECT_DOUBLE_EQ(r.recall, 1.0);
  // Without ignore regions the two precisions agree; an ignore region never changes recall.
  const auto plain = map_metrics(map, truth);
  EXPECT_EQ(plain.ignored, 0);
  EXPECT_DOUBLE_EQ(plain.precision_visible, plain.precision);
  // Only ignored heads: precision_visible undefined, precision 0.
  const auto only = map_metrics({P(0.06)}, {}, {}, {P(0.06)});
  EXPECT_EQ(only.ignored, 1);
  EXPECT_TRUE(std::isnan(only.precision_visible));
  EXPECT_DOUBLE_EQ(only.precision, 0.0);
}

TEST(MapMetrics, HungarianIsOptimalOnRandomMatrices) {
  // Against brute force over all permutations (3×3 .. 4×6, both orientations).
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(0, 1);
  for (int trial = 0; trial < 60; ++trial) {
    const int rows = 2 + trial % 3, cols = rows + (trial / 3) % 3;
    const bool flip = trial % 2;
    const int R = flip ? cols : rows, C = flip ? rows : cols;
    std::vector<double> cost(std::size_t(R * C));
    for (auto& c : cost) c = u(rng);
    const auto a = hungarian(cost, R, C);
    double got = 0;
    std::vector<int> used(std::size_t(C), 0);
    int assigned = 0;
    for (int i = 0; i < R; ++i)
      if (a[std::size_t(i)] >= 0) {
        got += cost[std::size_t(i * C + a[std::size_t(i)])];
        EXPECT_EQ(used[std::size_t(a[std::size_t(i)])]++, 0);
        ++assigned;
      }
    EXPECT_EQ(assigned, std::min(R, C));
    // brute force: permute the larger side
    const int small = std::min(R, C), large = std::max(R, C);
    std::vector<int> perm(static_cast<std::size_t>(large));
    for (int k = 0; k < large; ++k) perm[std::size_t(k)] = k;
    double best = 1e9;
    do {
      double s = 0;
      for (int k = 0; k < small; ++k)
        s += R <= C ? cost[std::size_t(k * C + perm[std::size_t(k)])] : cost[std::size_t(perm[std::size_t(k)] * C + k)];
      best = std::min(best, s);
    } while (std::next_permutation(perm.begin(), perm.end()));
    EXPECT_NEAR(got, best, 1e-12) << trial;
  }
  EXPECT_THROW(hungarian({1.0, 2.0}, 2, 2), Error);
}

TEST(SizeMetrics, HandComputed) {
  // errors: −10, 0, 5, 20, 2 → sorted −10 0 2 5 20 → MEDE 2; |e−2|: 12 2 3 18 0 → MAD 3;
  // |e|: 10 0 5 20 2 → median 5; RMSE sqrt((100+0+25+400+4)/5)
  const std::vector<double> truth{100, 110, 120, 130, 140};
  const std::vector<double> est{90, 110, 125, 150, 142};
  const auto m = size_metrics(est, truth);
  EXPECT_EQ(m.n, 5);
  EXPECT_DOUBLE_EQ(m.mede_mm, 2.0);
  EXPECT_DOUBLE_EQ(m.mad_mm, 3.0);
  EXPECT_DOUBLE_EQ(m.medae_mm, 5.0);
  EXPECT_NEAR(m.rmse_mm, std::sqrt(529.0 / 5), 1e-12);
  // Pearson by hand: mean est 123.4, mean truth 120
  double sab = 0, saa = 0, sbb = 0;
  for (int i = 0; i < 5; ++i) {
    sab += (est[i] - 123.4) * (truth[i] - 120);
    saa += (est[i] - 123.4) * (est[i] - 123.4);
    sbb += (truth[i] - 120) * (truth[i] - 120);
  }
  EXPECT_NEAR(m.pearson_r, sab / std::sqrt(saa * sbb), 1e-12);
  EXPECT_GT(m.pearson_r, 0.9);
}

TEST(SizeMetrics, EvenCountsBiasAndEdgeCases) {
  EXPECT_DOUBLE_EQ(median({4, 1, 3, 2}), 2.5);
  EXPECT_TRUE(std::isnan(median({})));
  // A constant bias: MEDE = bias, MAD = 0, r = 1.
  const auto b = size_metrics({95, 105, 115, 125}, {100, 110, 120, 130});
  EXPECT_DOUBLE_EQ(b.mede_mm, -5.0);
  EXPECT_DOUBLE_EQ(b.mad_mm, 0.0);
  EXPECT_NEAR(b.pearson_r, 1.0, 1e-12);
  EXPECT_TRUE(std::isnan(size_metrics({100, 100}, {90, 120}).pearson_r));  // no spread
  EXPECT_EQ(size_metrics({}, {}).n, 0);
  EXPECT_THROW(size_metrics({1.0}, {}), Error);
  EXPECT_THROW(size_metrics({NAN}, {1.0}), Error);
}
