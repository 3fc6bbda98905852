// Row arg-max and the median-frequency class weights shared by the networks and the GBDT.
#include <gtest/gtest.h>

#include <cmath>

#include "cropsight/core/class_scores.hpp"

using cropsight::argmax_rows;
using cropsight::median_frequency_weights;

TEST(ClassScores, ArgmaxRowsTakesTheFirstLargest) {
  const float s[] = {0.1f, 0.7f, 0.2f,  //
                     0.5f, 0.5f, 0.0f,  // tie: the first
                     0.0f, 0.0f, 0.9f};
  EXPECT_EQ(argmax_rows(s, 3, 3), (std::vector<int>{1, 0, 2}));
}

TEST(ClassScores, MedianFrequencyWeightsByHand) {
  // Present counts 10, 40, 90 -> median 40; class 2 absent -> weight 1.
  const std::vector<double> counts{10, 40, 0, 90};
  const auto w = median_frequency_weights(counts, 1.0);
  ASSERT_EQ(w.size(), 4u);
  EXPECT_DOUBLE_EQ(w[0], 4.0);
  EXPECT_DOUBLE_EQ(w[1], 1.0);
  EXPECT_DOUBLE_EQ(w[2], 1.0);
  EXPECT_DOUBLE_EQ(w[3], 40.0 / 90.0);
  const auto h = median_frequency_weights(counts, 0.5);  // the recipes' power
  EXPECT_DOUBLE_EQ(h[0], 2.0);
  EXPECT_DOUBLE_EQ(h[3], std::sqrt(40.0 / 90.0));
  for (double x : median_frequency_weights(counts, 0.0)) EXPECT_DOUBLE_EQ(x, 1.0);
  // Even number of present classes: the upper median (index n / 2), as both trainers used.
  EXPECT_DOUBLE_EQ(median_frequency_weights({1, 2, 3, 4}, 1.0)[0], 3.0);
  EXPECT_EQ(median_frequency_weights({0, 0}, 1.0), (std::vector<double>{1.0, 1.0}));
}
