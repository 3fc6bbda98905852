#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "cropsight/eval/detection_ap.hpp"

using namespace cropsight::eval;

namespace {
std::vector<int> range(int b, int e) {
  std::vector<int> v(std::size_t(e - b));
  std::iota(v.begin(), v.end(), b);
  return v;
}
}  // namespace

TEST(PointSetIou, SortedAndUnsorted) {
  const std::vector<int> a{5, 1, 3, 2}, b{2, 3, 4};
  EXPECT_DOUBLE_EQ(point_set_iou(a, b), 2.0 / 5.0);  // ∩ {2,3}, ∪ {1,2,3,4,5}
  EXPECT_DOUBLE_EQ(point_set_iou(range(0, 10), range(0, 8)), 0.8);
  EXPECT_DOUBLE_EQ(point_set_iou(range(0, 5), range(5, 9)), 0.0);
  EXPECT_DOUBLE_EQ(point_set_iou({}, {}), 0.0);
}

// Hand-computed: 4 instances; ranked T F T T F →
// precision 1, 1/2, 2/3, 3/4, 3/5; recall .25 .25 .5 .75 .75; envelope 1 .75 .75 .75 .6
// AP = .25·1 + .25·.75 + .25·.75 = 0.625
TEST(AveragePrecision, AllPointInterpolation) {
  std::vector<RankedHit> r{{0.5f, false}, {0.9f, true}, {0.7f, true}, {0.8f, false}, {0.6f, true}};
  EXPECT_DOUBLE_EQ(average_precision(r, 4), 0.625);
  EXPECT_DOUBLE_EQ(average_precision({{1.0f, true}, {0.5f, true}}, 2), 1.0);
  EXPECT_DOUBLE_EQ(average_precision({}, 3), 0.0);
  EXPECT_TRUE(std::isnan(average_precision({{1.0f, false}}, 0)));
}

// Frame 0: instances A = 0..9, B = 20..29; detections d1 (0.9) = 0..7 (IoU A 0.8), d2 (0.8) =
// 0..9 (IoU A 1, a duplicate), d3 (0.3) = 20..24 ∪ 30..34 (IoU B 1/3).
// Frame 1: instance C = 0..3; d4 (0.95) = 0..3 (IoU 1).
TEST(DetectionAp, GreedyMatchingOnNotYetMatchedInstances) {
  DetectionApAccumulator acc;
  const std::vector<int> d1 = range(0, 8), d2 = range(0, 10);
  std::vector<int> d3 = range(20, 25);
  for (int i = 30; i < 35; ++i) d3.push_back(i);
  acc.add_frame({range(0, 10), range(20, 30)}, {{0.9f, d1}, {0.8f, d2}, {0.3f, d3}});
  const std::vector<int> d4 = range(0, 4);
  acc.add_frame({range(0, 4)}, {{0.95f, d4}});
  EXPECT_EQ(acc.num_truth(), 3);
  EXPECT_EQ(acc.num_detections(), 4);
  // t = 0.5: d4 T, d1 T, d2 F (A already matched), d3 F → P 1 1 2/3 1/2, R 1/3 2/3 2/3 2/3 → 2/3
  EXPECT_NEAR(acc.ap(0.5), 2.0 / 3.0, 1e-12);
  // t = 0.85: d1 (0.8) fails and leaves A unmatched, so d2 takes it: T F T F → 1/3 + 1/3·2/3 = 5/9
  EXPECT_NEAR(acc.ap(0.85), 5.0 / 9.0, 1e-12);
  // 0.50 … 0.80 (7 thresholds) give 2/3, 0.85 … 0.95 (3) give 5/9.
  EXPECT_NEAR(acc.map50_95(), (7 * (2.0 / 3.0) + 3 * (5.0 / 9.0)) / 10.0, 1e-12);
  EXPECT_EQ(acc.true_positives(0.5, 0.0f), 2);
  EXPECT_EQ(acc.true_positives(0.5, 0.92f), 1);
}

TEST(DetectionAp, MissedInstancesLowerRecall) {
  DetectionApAccumulator acc;
  const std::vector<int> d = range(0, 10);
  acc.add_frame({range(0, 10), range(50, 60)}, {{1.0f, d}});
  EXPECT_DOUBLE_EQ(acc.ap(0.5), 0.5);
  DetectionApAccumulator empty;
  empty.add_frame({}, {});
  EXPECT_TRUE(std::isnan(empty.ap(0.5)));
}

// Instance B (20..29) is ignored (e.g. cut by the image border): it does not count, and d3
// (IoU 1 with B) is dropped from the ranking instead of being a false positive; d5 overlaps
// nothing and stays a false positive.
TEST(DetectionAp, IgnoredInstancesNeitherCountNorPenalise) {
  DetectionApAccumulator acc;
  const std::vector<int> d1 = range(0, 10), d3 = range(20, 30), d5 = range(40, 50);
  acc.add_frame({range(0, 10), range(20, 30)}, {{0.9f, d1}, {0.8f, d3}, {0.7f, d5}}, {false, true});
  EXPECT_EQ(acc.num_truth(), 1);
  // Ranked: d1 T, (d3 dropped), d5 F → AP = 1 (recall 1 reached at precision 1).
  EXPECT_DOUBLE_EQ(acc.ap(0.5), 1.0);
  DetectionApAccumulator counted;
  counted.add_frame({range(0, 10), range(20, 30)}, {{0.9f, d1}, {0.8f, d3}, {0.7f, d5}});
  EXPECT_DOUBLE_EQ(counted.ap(0.5), 1.0);  // both found: T T F
  DetectionApAccumulator worse;
  worse.add_frame({range(0, 10), range(20, 30)}, {{0.9f, d5}, {0.8f, d1}}, {false, true});
  EXPECT_DOUBLE_EQ(worse.ap(0.5), 0.5);  // F T: precision 1/2 at recall 1
}
