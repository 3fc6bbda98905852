#include <gtest/gtest.h>

#include "cropsight/core/error.hpp"
#include "cropsight/report/render.hpp"

namespace cropsight::report {
namespace {

TEST(Render, RobustDepthRangeIgnoresHolesAndOutliers) {
  DepthImage d(100, 1);
  for (int u = 0; u < 100; ++u) d.at(u, 0) = std::uint16_t(1000 + u);  // 1.000 .. 1.099 m
  d.at(0, 0) = 0;                                                      // hole
  d.at(99, 0) = 60000;                                                 // flying pixel
  const DepthRange r = robust_depth_range(d, 0.001);
  EXPECT_NEAR(r.near_m, 1.003, 0.0015);
  EXPECT_NEAR(r.far_m, 1.096, 0.0015);
  EXPECT_EQ(robust_depth_range(DepthImage(4, 4), 0.001).far_m, 1.0);  // no valid depth
  const DepthRange flat = robust_depth_range(DepthImage(4, 4, 1200), 0.001);
  EXPECT_NEAR(flat.far_m - flat.near_m, 0.01, 1e-9);
}

TEST(Render, DepthColormapNearIsRedFarIsBlueHolesBlack) {
  DepthImage d(3, 1);
  d.at(0, 0) = 1000;
  d.at(1, 0) = 2000;
  d.at(2, 0) = 0;
  const ColorImage c = depth_colormap(d, 0.001, {1.0, 2.0});
  EXPECT_GT(c.at(0, 0).r, c.at(0, 0).b);  // near: red end of turbo
  EXPECT_GT(c.at(1, 0).b, c.at(1, 0).r);  // far: blue end
  EXPECT_EQ(c.at(2, 0), (Rgb8{0, 0, 0}));
}

TEST(Render, LabelColorsAreDistinctAndStable) {
  EXPECT_EQ(label_color(0), (Rgb8{40, 40, 40}));
  EXPECT_EQ(label_color(5), label_color(5));
  for (std::uint32_t a = 1; a < 30; ++a)
    for (std::uint32_t b = a + 1; b < 30; ++b) EXPECT_FALSE(label_color(a) == label_color(b)) << a << " " << b;
}

TEST(Render, OutlinesAreTheInnerBoundaryOfEachInstance) {
  LabelImage l(6, 5);
  for (int v = 1; v <= 3; ++v)
    for (int u = 1; u <= 3; ++u) l.at(u, v) = 7;  // 3x3 square: 8 boundary pixels, centre inside
  ColorImage img(6, 5, Rgb8{1, 2, 3});
  draw_label_outlines(img, l, {255, 0, 0});
  int painted = 0;
  for (const auto& p : img.data) painted += p == Rgb8{255, 0, 0};
  EXPECT_EQ(painted, 8);
  EXPECT_EQ(img.at(2, 2), (Rgb8{1, 2, 3}));
  EXPECT_EQ(img.at(1, 1), (Rgb8{255, 0, 0}));
  ColorImage wrong(5, 5);
  EXPECT_THROW(draw_label_outlines(wrong, l), Error);
}

TEST(Render, Upscale) {
  ColorImage a(2, 1);
  a.at(1, 0) = {9, 9, 9};
  const ColorImage b = upscale(a, 3);
  EXPECT_EQ(b.width, 6);
  EXPECT_EQ(b.height, 3);
  EXPECT_EQ(b.at(5, 2), (Rgb8{9, 9, 9}));
  EXPECT_EQ(b.at(2, 2), (Rgb8{0, 0, 0}));
}

}  // namespace
}  // namespace cropsight::report
