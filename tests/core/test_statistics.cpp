#include "cropsight/core/statistics.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace cropsight;

TEST(Statistics, MedianOfOddAndEvenCounts) {
  EXPECT_DOUBLE_EQ(median({3, 1, 2}), 2.0);
  EXPECT_DOUBLE_EQ(median({4, 1, 3, 2}), 2.5);
  EXPECT_TRUE(std::isnan(median({})));
}

TEST(Statistics, QuantileIsTheNearestRankOfTheSortedValues) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-5, 5);
  std::vector<double> v(101);
  for (double& x : v) x = u(rng);
  std::vector<double> sorted = v;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_DOUBLE_EQ(quantile(v, 0.0), sorted.front());
  EXPECT_DOUBLE_EQ(quantile(v, 0.5), sorted[50]);
  EXPECT_DOUBLE_EQ(quantile(v, 0.99), sorted[99]);
  EXPECT_DOUBLE_EQ(quantile(v, 1.0), sorted.back());
  EXPECT_DOUBLE_EQ(quantile(v, 0.5), median(v));  // odd count: the same value
  EXPECT_TRUE(std::isnan(quantile({}, 0.5)));
}
