// COCO box AP (eval/coco_box_ap.hpp) on hand-made boxes with known answers.
#include <gtest/gtest.h>

#include <cmath>

#include "cropsight/eval/coco_box_ap.hpp"

namespace {
using cropsight::Detection2D;
using cropsight::eval::coco_box_ap;
using cropsight::eval::coco_box_ap_summary;
using cropsight::eval::CocoApImage;

Detection2D coco_box(float x1, float y1, float x2, float y2, float score = 1) { return {x1, y1, x2, y2, 0, score}; }

TEST(CocoBoxAp, PerfectDetectionsScoreOne) {
  const std::vector<CocoApImage> ims = {{{coco_box(0, 0, 10, 10)}, {coco_box(0, 0, 10, 10, 0.9f)}},
                                        {{coco_box(5, 5, 20, 20)}, {coco_box(5, 5, 20, 20, 0.8f)}}};
  const auto s = coco_box_ap_summary(ims);
  EXPECT_DOUBLE_EQ(s.ap50, 1.0);
  EXPECT_DOUBLE_EQ(s.ap50_95, 1.0);
  EXPECT_EQ(s.truths, 2);
  EXPECT_EQ(s.detections, 2);
}

TEST(CocoBoxAp, UsesOneHundredOnePointInterpolation) {
  // Ranked: TP, FP, TP over two truths: recall .5, .5, 1; precision 1, .5, 2/3. 101-point: recall
  // points 0..0.50 (51) take precision 1, 0.51..1 (50) take 2/3; all-point would give 0.8333.
  const std::vector<CocoApImage> ims = {
      {{coco_box(0, 0, 10, 10), coco_box(50, 50, 60, 60)},
       {coco_box(0, 0, 10, 10, 0.9f), coco_box(100, 100, 110, 110, 0.8f), coco_box(50, 50, 60, 60, 0.7f)}}};
  EXPECT_NEAR(coco_box_ap(ims, 0.5), (51.0 + 50.0 * 2.0 / 3.0) / 101.0, 1e-12);
}

TEST(CocoBoxAp, AveragesTenThresholds) {
  // IoU 0.78: a true positive at 0.50 ... 0.75 (6 of 10 thresholds), a false one above.
  const std::vector<CocoApImage> ims = {{{coco_box(0, 0, 10, 10)}, {coco_box(0, 0, 10, 7.8f, 0.9f)}}};
  const auto s = coco_box_ap_summary(ims);
  EXPECT_DOUBLE_EQ(s.ap50, 1.0);
  EXPECT_DOUBLE_EQ(s.ap75, 1.0);
  EXPECT_NEAR(s.ap50_95, 0.6, 1e-12);
}

TEST(CocoBoxAp, DuplicateIsFalsePositiveAndMissedTruthLowersRecall) {
  // Two truths, one found twice: TP then FP; recall stops at 0.5 → 51 of 101 points at precision 1.
  const std::vector<CocoApImage> ims = {{{coco_box(0, 0, 10, 10), coco_box(50, 50, 60, 60)},
                                         {coco_box(0, 0, 10, 10, 0.9f), coco_box(0, 0, 10, 9.5f, 0.8f)}}};
  EXPECT_NEAR(coco_box_ap(ims, 0.5), 51.0 / 101.0, 1e-12);
}

TEST(CocoBoxAp, TakesTheBestUnmatchedTruth) {
  // The second detection's best truth is taken; COCO moves it on to the other one (pascalvoc.py
  // would count a false positive).
  const std::vector<CocoApImage> ims = {{{coco_box(0, 0, 10, 10), coco_box(2, 0, 12, 10)},
                                         {coco_box(0, 0, 10, 10, 0.9f), coco_box(0.5f, 0, 10.5f, 10, 0.8f)}}};
  EXPECT_DOUBLE_EQ(coco_box_ap(ims, 0.5), 1.0);
}

TEST(CocoBoxAp, NoTruthIsNaN) { EXPECT_TRUE(std::isnan(coco_box_ap({{{}, {coco_box(0, 0, 1, 1)}}}, 0.5))); }

}  // namespace
