#include <gtest/gtest.h>

#include <cmath>

#include "cropsight/eval/binary_metrics.hpp"

using cropsight::eval::BinaryConfusion;

// Hand-computed: TP 40, FP 10, TN 45, FN 5 (N = 100).
TEST(BinaryMetrics, HandComputedMatrix) {
  BinaryConfusion c{40, 10, 45, 5};
  EXPECT_EQ(c.total(), 100);
  EXPECT_DOUBLE_EQ(c.accuracy(), 0.85);
  EXPECT_DOUBLE_EQ(c.precision(), 0.8);
  EXPECT_DOUBLE_EQ(c.recall(), 40.0 / 45.0);
  EXPECT_DOUBLE_EQ(c.specificity(), 45.0 / 55.0);
  EXPECT_DOUBLE_EQ(c.npv(), 0.9);
  EXPECT_DOUBLE_EQ(c.f1(), 80.0 / 95.0);
  // p_e = (50·45 + 50·55) / 100² = 0.5 → κ = (0.85 − 0.5) / 0.5 = 0.7
  EXPECT_NEAR(c.kappa(), 0.7, 1e-12);
}

// Unbalanced: TP 5, FP 3, TN 90, FN 2 → p_o = 0.95, p_e = (8·7 + 92·93)/10⁴ = 0.8612,
// κ = (0.95 − 0.8612) / 0.1388 = 0.639769
TEST(BinaryMetrics, KappaOnUnbalancedClasses) {
  BinaryConfusion c;
  for (int i = 0; i < 5; ++i) c.add(true, true);
  for (int i = 0; i < 3; ++i) c.add(false, true);
  for (int i = 0; i < 90; ++i) c.add(false, false);
  for (int i = 0; i < 2; ++i) c.add(true, false);
  EXPECT_EQ(c.tp, 5);
  EXPECT_EQ(c.fp, 3);
  EXPECT_EQ(c.tn, 90);
  EXPECT_EQ(c.fn, 2);
  EXPECT_NEAR(c.kappa(), (0.95 - 0.8612) / (1 - 0.8612), 1e-12);
  BinaryConfusion d{1, 0, 0, 0};
  d.merge(c);
  EXPECT_EQ(d.tp, 6);
}

TEST(BinaryMetrics, UndefinedRatiosAreNaN) {
  BinaryConfusion none;
  EXPECT_TRUE(std::isnan(none.accuracy()));
  EXPECT_TRUE(std::isnan(none.kappa()));
  BinaryConfusion all_negative{0, 0, 10, 0};
  EXPECT_TRUE(std::isnan(all_negative.precision()));
  EXPECT_TRUE(std::isnan(all_negative.recall()));
  EXPECT_DOUBLE_EQ(all_negative.specificity(), 1.0);
  EXPECT_DOUBLE_EQ(all_negative.kappa(), 1.0);  // perfect agreement, chance agreement 1
  BinaryConfusion chance{0, 10, 0, 0};          // always wrong on one class
  EXPECT_TRUE(std::isnan(chance.kappa()) || chance.kappa() <= 0.0);
}
