// The paper's metric on cases worked out by hand (the numbers in the comments are the hand
// computation; each case separates this metric from a near variant that gives another figure).
#include "cropsight/eval/voc_ap.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace {
using cropsight::eval::VocBox;
using cropsight::eval::VocImage;

VocBox box(double x1, double y1, double x2, double y2, double score = 1.0) { return {x1, y1, x2, y2, score}; }

TEST(VocIou, InclusivePixelAreas) {
  // 10x10 pixels each (0..9 inclusive); shifted by one column: 9*10 / (100 + 100 - 90).
  EXPECT_DOUBLE_EQ(cropsight::eval::voc_iou(box(0, 0, 9, 9), box(1, 0, 10, 9)), 90.0 / 110.0);
  // Half the rows: 50 / 100 = 0.5 exactly (exclusive areas would give 36 / 81).
  EXPECT_DOUBLE_EQ(cropsight::eval::voc_iou(box(0, 0, 9, 9), box(0, 0, 9, 4)), 0.5);
  // Touching boxes share one pixel column: 1*10 / (100 + 100 - 10).
  EXPECT_DOUBLE_EQ(cropsight::eval::voc_iou(box(0, 0, 9, 9), box(9, 0, 18, 9)), 10.0 / 190.0);
  EXPECT_EQ(cropsight::eval::voc_iou(box(0, 0, 9, 9), box(10, 0, 19, 9)), 0.0);
  EXPECT_EQ(cropsight::eval::voc_iou(box(0, 0, 9, 9), box(0, 20, 9, 29)), 0.0);
}

// Two images, three truths, four detections.
std::vector<VocImage> two_images() {
  std::vector<VocImage> im(2);
  im[0].truth = {box(0, 0, 9, 9), box(20, 0, 29, 9)};
  im[1].truth = {box(0, 0, 9, 9)};
  im[0].detections = {box(1, 0, 10, 9, 0.7),     // IoU 0.818 with a truth already taken: FP
                      box(0, 0, 9, 9, 0.9)};     // exact: TP
  im[1].detections = {box(50, 50, 59, 59, 0.8),  // nothing: FP
                      box(0, 0, 9, 4, 0.6)};     // IoU 0.5 exactly: TP at 0.5, FP at 0.75
  return im;
}

TEST(VocAp, HandWorkedTwoImages) {
  // Ranked: 0.9 TP, 0.8 FP, 0.7 FP, 0.6 TP; 3 truths. Precision 1, 1/2, 1/3, 1/2; recall 1/3,
  // 1/3, 1/3, 2/3. Envelope 1, 1/2, 1/2, 1/2 → AP = 1/3·1 + 1/3·1/2 = 1/2.
  EXPECT_NEAR(cropsight::eval::voc_ap(two_images(), 0.5), 0.5, 1e-12);
  // At 0.75 the last one is a FP: AP = 1/3.
  EXPECT_NEAR(cropsight::eval::voc_ap(two_images(), 0.75), 1.0 / 3.0, 1e-12);
  const auto s = cropsight::eval::voc_ap_summary(two_images());
  EXPECT_EQ(s.images, 2);
  EXPECT_EQ(s.truths, 3);
  EXPECT_EQ(s.detections, 4);
  EXPECT_NEAR(s.ap50, 0.5, 1e-12);
  EXPECT_NEAR(s.ap75, 1.0 / 3.0, 1e-12);
  // Thresholds 0.50 → AP 1/2; 0.55 … 0.80 (IoUs 1, 0.818 taken, 0.5) → 1/3 (six thresholds);
  // 0.85 … 0.95 → 1/3 (the exact box still matches). Mean = (1/2 + 9/3) / 10.
  EXPECT_NEAR(s.map50_95, (0.5 + 9.0 / 3.0) / 10.0, 1e-12);
}

TEST(VocAp, BestTruthTakenIsAFalsePositive) {
  // pascalvoc.py: a detection whose best-IoU truth is already matched is a FP even when another
  // truth would pass. Truths of 100 and 80 pixels; the second detection (90 pixels) has IoU
  // 0.9 with the taken one and 80/90 with the free one. Ranked TP, FP; 2 truths → AP = 1/2
  // (a best-unmatched-truth rule would give 1).
  std::vector<VocImage> im(1);
  im[0].truth = {box(0, 0, 9, 9), box(0, 0, 9, 7)};
  im[0].detections = {box(0, 0, 9, 9, 0.9), box(0, 0, 9, 8, 0.8)};
  EXPECT_NEAR(cropsight::eval::voc_ap(im, 0.5), 0.5, 1e-12);
}

TEST(VocAp, MissedTruthsAndEmptyCases) {
  std::vector<VocImage> im(2);
  im[0].truth = {box(0, 0, 9, 9)};
  im[1].truth = {box(0, 0, 9, 9)};  // never detected: recall stops at 1/2
  im[0].detections = {box(0, 0, 9, 9, 0.5)};
  EXPECT_NEAR(cropsight::eval::voc_ap(im, 0.5), 0.5, 1e-12);
  im[0].detections.clear();
  EXPECT_EQ(cropsight::eval::voc_ap(im, 0.5), 0.0);
  EXPECT_TRUE(std::isnan(cropsight::eval::voc_ap(std::vector<VocImage>(3), 0.5)));
}

TEST(VocAp, TiesKeepImageOrder) {
  // Equal scores: image order decides. FP (image 0) then TP (image 1): precision 0, 1/2 → AP
  // = 1·1/2; the other order would give 1.
  std::vector<VocImage> im(2);
  im[1].truth = {box(0, 0, 9, 9)};
  im[0].detections = {box(0, 0, 9, 9, 0.5)};
  im[1].detections = {box(0, 0, 9, 9, 0.5)};
  EXPECT_NEAR(cropsight::eval::voc_ap(im, 0.5), 0.5, 1e-12);
}

}  // namespace
