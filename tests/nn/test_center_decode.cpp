// Masks inside the boxes (nn::masks_in_boxes, center_decode.hpp) against the whole-image masks
// of masks_from_heads on the same heads.
#include <gtest/gtest.h>

#include <random>

#include "cropsight/nn/center_decode.hpp"

namespace center_decode_test {
using namespace cropsight;

// Two classes of random scores on 10x6 cells, an extra mask pass at twice the input: every path
// of the upsampling (bilinear between centres, the edge cells, averaged passes) is exercised.
nn::CenterNetHeads random_heads(nn::CenterNetConfig& cfg) {
  cfg.class_names = "grape,peduncle";
  cfg.input_width = 40, cfg.input_height = 24;
  nn::CenterNetHeads h;
  h.classes = 2, h.out_w = 10, h.out_h = 6;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> score(0.f, 1.f);
  h.mask.resize(2 * 60);
  for (auto& s : h.mask) s = score(rng);
  nn::CenterNetHeads::MaskPass p;
  p.input_w = 80, p.input_h = 48, p.out_w = 20, p.out_h = 12;
  p.mask.resize(2 * 240);
  for (auto& s : p.mask) s = score(rng);
  h.extra_masks.push_back(p);
  return h;
}

bool inside_any(const std::vector<Detection2D>& boxes, int c, int u, int v) {
  for (const auto& b : boxes)
    if (b.class_id == c && float(u) + 1 > b.x1 && float(u) < b.x2 && float(v) + 1 > b.y1 && float(v) < b.y2)
      return true;
  return false;
}

TEST(MasksInBoxes, EqualTheWholeImageMasksInsideTheBoxesAndAreEmptyOutside) {
  nn::CenterNetConfig cfg;
  const nn::CenterNetHeads h = random_heads(cfg);
  const int w = 97, hgt = 61;  // odd: a letterbox border and fractional scales
  // Overlapping and touching boxes of class 0, one of class 1 beyond the image, one empty.
  const std::vector<Detection2D> boxes = {{3.5f, 2.2f, 30.1f, 20.0f, 0, 0.9f},   {20.0f, 10.0f, 50.0f, 40.7f, 0, 0.5f},
                                          {50.0f, 5.0f, 60.0f, 9.0f, 0, 0.4f},   {70.3f, 40.0f, 140.0f, 90.0f, 1, 0.8f},
                                          {10.0f, 10.0f, 10.0f, 30.0f, 1, 0.3f}, {0.0f, 50.0f, 4.0f, 61.0f, 1, 0.2f}};
  for (const char* mode : {"bilinear", "nearest"}) {
    cfg.mask_upsampling = mode;
    const auto full = nn::masks_from_heads(h, cfg, w, hgt, 0.5f);
    const auto boxed = nn::masks_in_boxes(h, cfg, boxes, w, hgt, 0.5f);
    ASSERT_EQ(boxed.size(), 2u);
    int inside_on = 0;
    for (int c = 0; c < 2; ++c)
      for (int v = 0; v < hgt; ++v)
        for (int u = 0; u < w; ++u) {
          const bool in = inside_any(boxes, c, u, v);
          EXPECT_EQ(boxed[std::size_t(c)].at(u, v), in ? full[std::size_t(c)].at(u, v) : 0)
              << mode << " class " << c << " pixel " << u << "," << v;
          inside_on += in && boxed[std::size_t(c)].at(u, v) != 0;
        }
    EXPECT_GT(inside_on, 100) << mode;  // random scores: about half the boxes' pixels are on
  }
  // No boxes: nothing is computed and every mask is empty.
  for (const auto& m : nn::masks_in_boxes(h, cfg, {}, w, hgt)) EXPECT_EQ(m.data, std::vector<std::uint8_t>(w * hgt, 0));
}

}  // namespace center_decode_test
