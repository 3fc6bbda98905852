#include <gtest/gtest.h>

#include <cmath>

#include "cropsight/core/error.hpp"
#include "cropsight/eval/segmentation_metrics.hpp"

namespace {
using cropsight::eval::ConfusionMatrix;

TEST(SegmentationMetrics, HandMadeThreeClassMatrix) {
  // rows = truth, cols = prediction
  //        p0 p1 p2
  // t0  [  5  1  0 ]
  // t1  [  2  3  1 ]
  // t2  [  0  0  4 ]
  ConfusionMatrix m(3);
  m.add(0, 0, 5), m.add(0, 1, 1);
  m.add(1, 0, 2), m.add(1, 1, 3), m.add(1, 2, 1);
  m.add(2, 2, 4);
  EXPECT_EQ(m.total(), 16);
  EXPECT_DOUBLE_EQ(m.overall_accuracy(), 12.0 / 16.0);
  EXPECT_DOUBLE_EQ(m.class_accuracy(0), 5.0 / 6.0);
  EXPECT_DOUBLE_EQ(m.class_accuracy(1), 3.0 / 6.0);
  EXPECT_DOUBLE_EQ(m.class_accuracy(2), 1.0);
  // IoU = TP / (row + col - TP)
  EXPECT_DOUBLE_EQ(m.class_iou(0), 5.0 / (6 + 7 - 5));
  EXPECT_DOUBLE_EQ(m.class_iou(1), 3.0 / (6 + 4 - 3));
  EXPECT_DOUBLE_EQ(m.class_iou(2), 4.0 / (4 + 5 - 4));
  EXPECT_DOUBLE_EQ(m.mean_accuracy(), (5.0 / 6 + 0.5 + 1.0) / 3);
  EXPECT_DOUBLE_EQ(m.mean_iou(), (5.0 / 8 + 3.0 / 7 + 4.0 / 5) / 3);
}

TEST(SegmentationMetrics, AbsentClassIsExcludedFromMeans) {
  ConfusionMatrix m(3);
  m.add(std::vector<int>{0, 0, 1, 1}, std::vector<int>{0, 1, 1, 1});
  EXPECT_TRUE(std::isnan(m.class_accuracy(2)));
  EXPECT_TRUE(std::isnan(m.class_iou(2)));
  EXPECT_DOUBLE_EQ(m.mean_accuracy(), (0.5 + 1.0) / 2);
  EXPECT_DOUBLE_EQ(m.mean_iou(), (1.0 / 2 + 2.0 / 3) / 2);
  // A class predicted but never true has accuracy NaN but IoU 0.
  m.add(0, 2);
  EXPECT_TRUE(std::isnan(m.class_accuracy(2)));
  EXPECT_DOUBLE_EQ(m.class_iou(2), 0.0);
}

TEST(SegmentationMetrics, MergeAndRangeChecks) {
  ConfusionMatrix a(2), b(2);
  a.add(0, 0, 3);
  b.add(1, 0, 1);
  a.merge(b);
  EXPECT_EQ(a.at(1, 0), 1);
  EXPECT_DOUBLE_EQ(a.overall_accuracy(), 0.75);
  EXPECT_THROW(a.add(2, 0), cropsight::Error);
  EXPECT_THROW(a.add(std::vector<int>{0}, std::vector<int>{0, 1}), cropsight::Error);
  EXPECT_THROW(a.merge(ConfusionMatrix(3)), cropsight::Error);
  EXPECT_TRUE(std::isnan(ConfusionMatrix(2).overall_accuracy()));
}
}  // namespace
