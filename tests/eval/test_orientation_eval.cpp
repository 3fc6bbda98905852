// eval/orientation_eval: the modulo-180° error and the grouped figures on hand-computed samples.
#include <gtest/gtest.h>

#include "cropsight/eval/orientation_eval.hpp"

namespace cropsight::eval {
namespace {

TEST(AxisAngleError, IsTheSmallestDifferenceModulo180) {
  EXPECT_DOUBLE_EQ(axis_angle_error_deg(179, 1), 2);
  EXPECT_DOUBLE_EQ(axis_angle_error_deg(1, 179), 2);
  EXPECT_DOUBLE_EQ(axis_angle_error_deg(0, 90), 90);
  EXPECT_DOUBLE_EQ(axis_angle_error_deg(45, 225), 0);
  EXPECT_DOUBLE_EQ(axis_angle_error_deg(135, 10), 55);
  EXPECT_DOUBLE_EQ(axis_angle_error_deg(0, -10), 10);
}

TEST(SummariseOrientation, GroupsByLightAngleAndPotato) {
  std::vector<OrientationSample> s = {
      {"a", 1, "high", 0, true, 178, 2.0},   // 2°
      {"b", 1, "low", 45, true, 51, 4.0},    // 6°
      {"c", 2, "high", 135, false, 0, 0.0},  // failure: 90°
      {"d", 2, "low", 90, true, 86, 6.0},    // 4°
  };
  const auto e = summarise_orientation(s);
  EXPECT_EQ(e.all.count, 4);
  EXPECT_EQ(e.all.failures, 1);
  EXPECT_DOUBLE_EQ(e.all.mae_deg, (2 + 6 + 90 + 4) / 4.0);
  EXPECT_DOUBLE_EQ(e.all.max_deg, 90);
  EXPECT_DOUBLE_EQ(e.ms_per_potato, 3.0);
  ASSERT_EQ(e.per_light.size(), 2u);
  EXPECT_EQ(e.per_light[0].key, "high");
  EXPECT_DOUBLE_EQ(e.per_light[0].mae_deg, 46);
  EXPECT_DOUBLE_EQ(e.per_light[0].std_deg, 44);
  ASSERT_EQ(e.per_angle.size(), 4u);
  EXPECT_EQ(e.per_angle[0].key, "0");
  EXPECT_EQ(e.per_angle[3].key, "135");
  ASSERT_EQ(e.per_potato.size(), 2u);
  EXPECT_DOUBLE_EQ(e.per_potato[0].mae_deg, 4);
}

TEST(SummariseOrientation, EmptyIsZero) {
  const auto e = summarise_orientation({});
  EXPECT_EQ(e.all.count, 0);
  EXPECT_EQ(e.ms_per_potato, 0);
}

}  // namespace
}  // namespace cropsight::eval
