// Weighted boxes fusion (core/box_fusion.hpp): the cluster rule, the weighted box, the score over
// the number of detectors, and the FusedDetector around scripted detectors.
#include <gtest/gtest.h>

#include "cropsight/core/box_fusion.hpp"
#include "cropsight/core/error.hpp"

namespace {

using cropsight::BoxFusionConfig;
using cropsight::Detection2D;
using cropsight::weighted_boxes_fusion;

Detection2D fusion_box(float x1, float y1, float x2, float y2, float score, int cls = 0) {
  Detection2D d;
  d.x1 = x1, d.y1 = y1, d.x2 = x2, d.y2 = y2, d.score = score, d.class_id = cls;
  return d;
}

class ScriptedDetector final : public cropsight::Detector2D {
 public:
  ScriptedDetector(std::vector<Detection2D> boxes, std::vector<std::string> names)
      : boxes_(std::move(boxes)), names_(std::move(names)) {}
  std::vector<Detection2D> detect(const cropsight::DetectorInput&) override { return boxes_; }
  std::vector<std::string> class_names() const override { return names_; }

 private:
  std::vector<Detection2D> boxes_;
  std::vector<std::string> names_;
};

TEST(BoxFusion, AgreeingBoxesBecomeTheirScoreWeightedMean) {
  // IoU of the two boxes: 90 x 100 / (100 x 100 + 100 x 100 - 9000) = 0.818 >= 0.55.
  const auto out = weighted_boxes_fusion({{fusion_box(0, 0, 100, 100, 0.6f)}, {fusion_box(10, 0, 110, 100, 0.2f)}});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_FLOAT_EQ(out[0].x1, (0.6f * 0 + 0.2f * 10) / 0.8f);
  EXPECT_FLOAT_EQ(out[0].x2, (0.6f * 100 + 0.2f * 110) / 0.8f);
  EXPECT_FLOAT_EQ(out[0].y1, 0.f);
  EXPECT_FLOAT_EQ(out[0].score, (0.6f + 0.2f) / 2);
}

TEST(BoxFusion, ABoxOneDetectorAloneSawKeepsItsShareOfTheScore) {
  // IoU 0.33 < 0.55: two clusters; each box keeps itself, its score halved (two detectors).
  const auto out = weighted_boxes_fusion({{fusion_box(0, 0, 100, 100, 0.8f)}, {fusion_box(50, 0, 150, 100, 0.5f)}});
  ASSERT_EQ(out.size(), 2u);
  EXPECT_FLOAT_EQ(out[0].score, 0.4f);
  EXPECT_FLOAT_EQ(out[0].x1, 0.f);
  EXPECT_FLOAT_EQ(out[1].score, 0.25f);
  EXPECT_FLOAT_EQ(out[1].x1, 50.f);
}

TEST(BoxFusion, AgreementOutranksOneDetectorsHigherScore) {
  // The point of fusing: a box both detectors saw at 0.5 ranks above one only the CNN saw at 0.9.
  const auto out = weighted_boxes_fusion(
      {{fusion_box(0, 0, 50, 50, 0.5f)}, {fusion_box(0, 0, 50, 50, 0.5f), fusion_box(200, 200, 260, 260, 0.9f)}});
  ASSERT_EQ(out.size(), 2u);
  EXPECT_FLOAT_EQ(out[0].score, 0.5f);
  EXPECT_FLOAT_EQ(out[0].x2, 50.f);
  EXPECT_FLOAT_EQ(out[1].score, 0.45f);
}

TEST(BoxFusion, BoxesOfOneDetectorNeverFuse) {
  // Two touching potatoes from the same detector stay two boxes, whatever their overlap.
  const auto out = weighted_boxes_fusion({{fusion_box(0, 0, 100, 100, 0.9f), fusion_box(5, 5, 105, 105, 0.8f)}, {}});
  EXPECT_EQ(out.size(), 2u);
}

TEST(BoxFusion, ClassesNeverFuse) {
  const auto out =
      weighted_boxes_fusion({{fusion_box(0, 0, 100, 100, 0.9f, 0)}, {fusion_box(0, 0, 100, 100, 0.9f, 1)}});
  ASSERT_EQ(out.size(), 2u);
  EXPECT_NE(out[0].class_id, out[1].class_id);
}

TEST(BoxFusion, TheThresholdDecidesTheCluster) {
  const std::vector<std::vector<Detection2D>> in{{fusion_box(0, 0, 100, 100, 0.6f)},
                                                 {fusion_box(20, 0, 120, 100, 0.6f)}};
  // IoU = 80 x 100 / 12000 = 0.667.
  BoxFusionConfig strict;
  strict.iou_threshold = 0.7;
  EXPECT_EQ(weighted_boxes_fusion(in, strict).size(), 2u);
  BoxFusionConfig loose;
  loose.iou_threshold = 0.6;
  EXPECT_EQ(weighted_boxes_fusion(in, loose).size(), 1u);
}

TEST(BoxFusion, FusedDetectorRunsEveryDetectorAndChecksTheirClasses) {
  std::vector<std::unique_ptr<cropsight::Detector2D>> two;
  two.push_back(std::make_unique<ScriptedDetector>(std::vector{fusion_box(0, 0, 40, 40, 0.4f)},
                                                   std::vector<std::string>{"potato"}));
  two.push_back(std::make_unique<ScriptedDetector>(std::vector{fusion_box(2, 0, 42, 40, 0.8f)},
                                                   std::vector<std::string>{"potato"}));
  cropsight::FusedDetector fused(std::move(two));
  const auto out = fused.detect({});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_FLOAT_EQ(out[0].score, 0.6f);
  EXPECT_EQ(fused.class_names(), std::vector<std::string>{"potato"});

  std::vector<std::unique_ptr<cropsight::Detector2D>> mixed;
  mixed.push_back(std::make_unique<ScriptedDetector>(std::vector<Detection2D>{}, std::vector<std::string>{"potato"}));
  mixed.push_back(std::make_unique<ScriptedDetector>(std::vector<Detection2D>{}, std::vector<std::string>{"grape"}));
  EXPECT_THROW(cropsight::FusedDetector(std::move(mixed)), cropsight::Error);
}

}  // namespace
