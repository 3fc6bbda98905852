// The detector evaluator (nn/detector_eval.hpp) on hand-made boxes and masks.
#include <gtest/gtest.h>

#include <cmath>

#include "cropsight/core/error.hpp"
#include "cropsight/nn/center_decode.hpp"
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

// The pixels set in `m`, each expected inside [u0, u1) x [v0, v1).
int pixels_on_all_inside(const GrayImage& m, int u0, int u1, int v0, int v1) {
  int on = 0;
  for (int v = 0; v < m.height; ++v)
    for (int u = 0; u < m.width; ++u)
      if (m.at(u, v)) {
        ++on;
        EXPECT_TRUE(u >= u0 && u < u1 && v >= v0 && v < v1) << u << "," << v;
      }
  return on;
}

TEST(DetectorEvaluator, MaskHeadMapsBackThroughTheLetterbox) {
  nn::CenterNetConfig cfg;
  cfg.input_width = 32, cfg.input_height = 32;
  cfg.mask_upsampling = "nearest";
  nn::CenterNetHeads h;
  h.classes = 1, h.out_w = 8, h.out_h = 8;
  h.mask.assign(64, 0.f);
  h.mask[2 * 8 + 1] = 0.9f;  // cell x 1, y 2
  // A 64x64 image is scaled by 1/2: the cell covers image pixels x 8..15, y 16..23.
  const auto m = nn::masks_from_heads(h, cfg, 64, 64, 0.5f);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(pixels_on_all_inside(m[0], 8, 16, 16, 24), 64);
}

// Multi-scale mask test: a pixel's score is the mean of the main head's and each extra pass's,
// each mapped through its own letterbox (an extra pass at twice the input has cells half as large
// in the image), and calibration sees the same averaged scores.
TEST(DetectorEvaluator, ExtraMaskPassesAreAveragedThroughTheirOwnLetterbox) {
  nn::CenterNetConfig cfg;
  cfg.input_width = 32, cfg.input_height = 32;
  cfg.mask_upsampling = "nearest";
  nn::CenterNetHeads h;
  h.classes = 1, h.out_w = 8, h.out_h = 8;
  h.mask.assign(64, 0.2f);
  nn::CenterNetHeads::MaskPass p;
  p.input_w = 64, p.input_h = 64, p.out_w = 16, p.out_h = 16;
  p.mask.assign(256, 0.2f);
  p.mask[5 * 16 + 3] = 1.0f;  // cell x 3, y 5 of the 64x64 input: image pixels x 12..15, y 20..23
  h.extra_masks.push_back(p);
  // 64x64 image: the main head's cells cover 8x8 pixels, the extra pass's 4x4.
  const auto m = nn::masks_from_heads(h, cfg, 64, 64, 0.55f);  // (0.2 + 1.0) / 2 = 0.6 only in that cell
  EXPECT_EQ(pixels_on_all_inside(m[0], 12, 16, 20, 24), 16);
  EXPECT_EQ(nn::masks_from_heads(h, cfg, 64, 64, 0.65f)[0].data, std::vector<std::uint8_t>(64 * 64, 0));
  // Calibration bins the averaged scores: truth = exactly that 4x4 block, so the best threshold
  // lies in (0.2, 0.6] and gives IoU 1; the one nearest 0.5 of those is 0.5.
  nn::DetectionSample s;
  s.image = ColorImage(64, 64);
  s.masks = {GrayImage(64, 64, 0)};
  for (int v = 20; v < 24; ++v)
    for (int u = 12; u < 16; ++u) s.masks[0].at(u, v) = 255;
  nn::MaskCalibration cal(1);
  cal.add(h, cfg, s);
  EXPECT_FLOAT_EQ(cal.thresholds()[0], 0.5f);
  // A pass whose mask does not fit its cells is an error, not a read past the end.
  h.extra_masks[0].mask.resize(10);
  EXPECT_THROW(nn::masks_from_heads(h, cfg, 64, 64, 0.5f), Error);
}

TEST(DetectorEvaluator, MaskInputsAreCheckedWxHLists) {
  nn::CenterNetConfig cfg;
  EXPECT_TRUE(cfg.mask_input_sizes().empty());
  cfg.mask_inputs = "768x448, 896X512";
  EXPECT_EQ(cfg.mask_input_sizes(), (std::vector<std::pair<int, int>>{{768, 448}, {896, 512}}));
  for (const char* bad : {"768", "768x", "770x448", "768x448x2", "0x0", "x448", "768x448,abc", "8192x448", "-32x64"}) {
    cfg.mask_inputs = bad;
    EXPECT_THROW(cfg.validate("m.pt"), Error) << bad;
  }
}

// Bilinear upsampling interpolates between cell centres: on a ramp of scores across the cells
// the mask's edge lies where the interpolated score crosses the threshold, not at a cell border.
TEST(DetectorEvaluator, BilinearMaskEdgeFollowsTheScoreBetweenCellCentres) {
  nn::CenterNetConfig cfg;
  cfg.input_width = 32, cfg.input_height = 32;  // heads 8x8: one cell = 4 input = 8 image pixels
  nn::CenterNetHeads h;
  h.classes = 1, h.out_w = 8, h.out_h = 8;
  h.mask.resize(64);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) h.mask[std::size_t(y * 8 + x)] = float(x) / 7.0f;
  auto first_on = [&](const GrayImage& m, int v) {
    for (int u = 0; u < m.width; ++u)
      if (m.at(u, v)) return u;
    return -1;
  };
  // Pixel u's centre lies at cell coordinate (u + 0.5) / 8; cell centres at k + 0.5. Score 0.55
  // is reached at 3.85 cells past the first centre: pixel 35 (34 gives 0.545). The cell under
  // pixel 32 already scores 4/7 = 0.571, so nearest switches on there.
  const auto bilinear = nn::masks_from_heads(h, cfg, 64, 64, 0.55f);
  cfg.mask_upsampling = "nearest";
  const auto nearest = nn::masks_from_heads(h, cfg, 64, 64, 0.55f);
  for (int v : {0, 31, 63}) {
    EXPECT_EQ(first_on(bilinear[0], v), 35) << "row " << v;
    EXPECT_EQ(first_on(nearest[0], v), 32) << "row " << v;
  }
  // Outside the outermost centres the edge cell's score holds (no extrapolation).
  EXPECT_TRUE(bilinear[0].at(63, 10));
  EXPECT_FALSE(bilinear[0].at(0, 10));
  cfg.mask_upsampling = "cubic";
  EXPECT_THROW(cfg.validate("test"), Error);
}

// Two classes on a 32x32 image (input 32x32, heads 8x8: one cell = 4x4 pixels). Class 0's mask
// head scores 0.8 on its truth and 0.3 elsewhere; class 1 (thin, like a peduncle) scores only 0.2
// on its truth and 0.04 elsewhere, so 0.5 finds none of it.
struct TwoClassScene {
  nn::CenterNetConfig cfg;
  nn::CenterNetHeads heads;
  nn::DetectionSample sample;
  TwoClassScene() {
    cfg.class_names = "bunch,peduncle";
    cfg.input_width = 32, cfg.input_height = 32;
    cfg.mask_upsampling = "nearest";  // the scores are constant per cell: exact expected masks
    heads.classes = 2, heads.out_w = 8, heads.out_h = 8;
    heads.mask.assign(2 * 64, 0.f);
    sample.name = "scene.png";
    sample.image = ColorImage(32, 32);
    sample.masks = {GrayImage(32, 32, 0), GrayImage(32, 32, 0)};
    for (int cy = 0; cy < 8; ++cy)
      for (int cx = 0; cx < 8; ++cx) {
        const bool bunch = cx >= 2 && cx < 6 && cy >= 3, stem = cx == 4 && cy < 3;
        heads.mask[std::size_t(cy * 8 + cx)] = bunch ? 0.8f : 0.3f;
        heads.mask[std::size_t(64 + cy * 8 + cx)] = stem ? 0.2f : 0.04f;
        for (int v = 4 * cy; v < 4 * cy + 4; ++v)
          for (int u = 4 * cx; u < 4 * cx + 4; ++u) {
            if (bunch) sample.masks[0].at(u, v) = 1;
            if (stem) sample.masks[1].at(u, v) = 1;
          }
      }
  }
};

TEST(MaskCalibration, PicksEachClassesBestIouThresholdNearestOneHalf) {
  const TwoClassScene s;
  nn::MaskCalibration cal(2);
  cal.add(s.heads, s.cfg, s.sample);
  const auto t = cal.thresholds();
  ASSERT_EQ(t.size(), 2u);
  // Class 0: every threshold in (0.3, 0.8] separates it exactly; the nearest to 0.5 is 0.5.
  EXPECT_FLOAT_EQ(t[0], 0.5f);
  // Class 1: (0.04, 0.2] separates it: 0.05 ... 0.20; the nearest to 0.5 is 0.20.
  EXPECT_FLOAT_EQ(t[1], 0.2f);
  // The masks at those thresholds are the truth.
  nn::CenterNetConfig cfg = s.cfg;
  cfg.mask_thresholds = "0.5,0.2";
  const auto m = nn::masks_from_heads(s.heads, cfg, 32, 32);
  nn::DetectorEvaluator ev(cfg.names());
  ev.add(s.sample, {}, m);
  const auto r = ev.score();
  EXPECT_DOUBLE_EQ(r.classes[0].iou, 1.0);
  EXPECT_DOUBLE_EQ(r.classes[1].iou, 1.0);
  // At one threshold of 0.5 for both, the thin class has no pixel.
  nn::DetectorEvaluator flat(cfg.names());
  flat.add(s.sample, {}, nn::masks_from_heads(s.heads, cfg, 32, 32, 0.5f));
  EXPECT_EQ(flat.score().classes[1].predicted_pixels, 0);
}

TEST(MaskCalibration, AClassWithoutTruthPixelsKeepsOneHalf) {
  TwoClassScene s;
  s.sample.masks[1] = GrayImage(32, 32, 0);
  nn::MaskCalibration cal(2);
  cal.add(s.heads, s.cfg, s.sample);
  nn::DetectionSample unmasked = s.sample;
  unmasked.masks.clear();
  cal.add(s.heads, s.cfg, unmasked);  // adds nothing
  EXPECT_FLOAT_EQ(cal.thresholds()[1], 0.5f);
}

TEST(MaskCalibration, ConfigChecksTheThresholdList) {
  nn::CenterNetConfig cfg;
  cfg.class_names = "a,b";
  EXPECT_EQ(cfg.mask_threshold_values(), (std::vector<float>{0.5f, 0.5f}));  // empty: 0.5 each
  cfg.mask_thresholds = "0.65, 0.05";
  EXPECT_EQ(cfg.mask_threshold_values(), (std::vector<float>{0.65f, 0.05f}));
  for (const char* bad : {"0.5", "0.5,0.5,0.5", "0.5,1", "0,0.5", "0.5,x", "0.5,nan", "0.5,0.2e"}) {
    cfg.mask_thresholds = bad;
    EXPECT_THROW(cfg.validate("m.pt"), Error) << bad;
  }
}

}  // namespace
