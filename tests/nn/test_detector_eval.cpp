// The detector evaluator (nn/detector_eval.hpp) on hand-made boxes and masks.
#include <gtest/gtest.h>

#include <cmath>

#include "cropsight/nn/detector_eval.hpp"

namespace {
using namespace cropsight;

GrayImage half_mask(int w, int h, bool left) {
  GrayImage m(w, h, 0);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u)
      if (left ? u < w / 2 : v < h / 2) m.at(u, v) = 1;
  return m;
}

TEST(DetectorEvaluator, BoxApAndMaskIouPerClass) {
  nn::DetectorEvaluator ev({"grape", "peduncle"});
  nn::DetectionSample s;
  s.name = "a.png";
  s.boxes = {{0, 0, 10, 10, 0, 1}, {20, 20, 24, 30, 1, 1}};
  // grape: truth left half, predicted top half of a 4x4 image → TP 4, FN 4, FP 4.
  // peduncle: truth left half, predicted the same.
  s.masks = {half_mask(4, 4, true), half_mask(4, 4, true)};
  ev.add(s, {{0, 0, 10, 10, 0, 0.9f}}, {half_mask(4, 4, false), half_mask(4, 4, true)});
  const auto r = ev.score();
  ASSERT_EQ(r.classes.size(), 2u);
  EXPECT_EQ(r.images, 1);
  EXPECT_EQ(r.masked_images, 1);
  EXPECT_DOUBLE_EQ(r.classes[0].ap50, 1.0);
  EXPECT_DOUBLE_EQ(r.classes[1].ap50, 0.0);  // its one truth box is missed
  EXPECT_NEAR(r.classes[0].iou, 4.0 / 12.0, 1e-12);
  EXPECT_NEAR(r.classes[0].pixel_accuracy, 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(r.classes[1].iou, 1.0);
  EXPECT_DOUBLE_EQ(r.classes[1].pixel_accuracy, 1.0);
  EXPECT_EQ(r.classes[0].truth_pixels, 8);
  EXPECT_EQ(r.classes[0].predicted_pixels, 8);
}

TEST(DetectorEvaluator, ImagesWithoutMasksCountForBoxesOnly) {
  nn::DetectorEvaluator ev({"x"});
  nn::DetectionSample s;
  s.boxes = {{0, 0, 10, 10, 0, 1}};
  ev.add(s, {{0, 0, 10, 10, 0, 0.5f}}, {});
  const auto r = ev.score();
  EXPECT_EQ(r.masked_images, 0);
  EXPECT_DOUBLE_EQ(r.classes[0].ap50, 1.0);
  EXPECT_TRUE(std::isnan(r.classes[0].iou));
}

TEST(DetectorEvaluator, MaskHeadMapsBackThroughTheLetterbox) {
  nn::CenterNetConfig cfg;
  cfg.input_width = 32, cfg.input_height = 32;
  nn::CenterNetHeads h;
  h.classes = 1, h.out_w = 8, h.out_h = 8;
  h.mask.assign(64, 0.f);
  h.mask[2 * 8 + 1] = 0.9f;  // cell x 1, y 2
  // A 64x64 image is scaled by 1/2: the cell covers image pixels x 8..15, y 16..23.
  const auto m = nn::masks_from_heads(h, cfg, 64, 64, 0.5f);
  ASSERT_EQ(m.size(), 1u);
  int on = 0;
  for (int v = 0; v < 64; ++v)
    for (int u = 0; u < 64; ++u)
      if (m[0].at(u, v)) {
        ++on;
        EXPECT_TRUE(u >= 8 && u < 16 && v >= 16 && v < 24) << u << "," << v;
      }
  EXPECT_EQ(on, 64);
}

}  // namespace
