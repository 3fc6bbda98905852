#include <gtest/gtest.h>

#include <cstdlib>

#include "cropsight/pipeline/broccoli/depth_encoding.hpp"

namespace {

using cropsight::DepthImage;
using cropsight::Rgb8;
using cropsight::pipeline::broccoli::encode_depth_for_cnn;

// Soil at 1.2 m, a 20 x 20 px block 0.3 m above it (0.9 m) at columns/rows 20..39, one pixel
// without a return on the soil.
DepthImage block_on_soil() {
  DepthImage d(64, 60, 1200);
  for (int v = 20; v < 40; ++v)
    for (int u = 20; u < 40; ++u) d.at(u, v) = 900;
  d.at(5, 50) = 0;
  return d;
}

bool near(int a, int b) { return std::abs(a - b) <= 1; }  // float rounding before the 8-bit cast

}  // namespace

TEST(DepthEncoding, ChannelsAreHeightReliefAndEdges) {
  const auto img = encode_depth_for_cnn(block_on_soil(), 0.001);
  ASSERT_EQ(img.width, 64);
  ASSERT_EQ(img.height, 60);
  // Soil far from the block: height 0 (1: a return), flat, no edge.
  const Rgb8 soil = img.at(55, 10);
  EXPECT_EQ(soil.r, 1);
  EXPECT_TRUE(near(soil.g, 128)) << int(soil.g);
  EXPECT_EQ(soil.b, 0);
  // Block centre: 0.3 m / 0.5 m of 255; its 15 x 15 window lies on the block: flat, no edge.
  const Rgb8 top = img.at(30, 30);
  EXPECT_TRUE(near(top.r, 153)) << int(top.r);
  EXPECT_TRUE(near(top.g, 128)) << int(top.g);
  EXPECT_EQ(top.b, 0);
  // The block's corner stands above its window's mean (a dome), the soil beside it below.
  EXPECT_GT(img.at(20, 20).g, 200);
  EXPECT_LT(img.at(19, 30).g, 100);
  // A 0.3 m step is far above 0.02 m per pixel: saturated edge on both sides of it.
  EXPECT_EQ(img.at(20, 30).b, 255);
  EXPECT_EQ(img.at(19, 30).b, 255);
  // No return: the neutral pixel.
  EXPECT_EQ(img.at(5, 50), (Rgb8{0, 128, 0}));
}

TEST(DepthEncoding, FrameWithoutReturnsIsNeutral) {
  const auto img = encode_depth_for_cnn(DepthImage(16, 12, 0), 0.001);
  for (const Rgb8& p : img.data) EXPECT_EQ(p, (Rgb8{0, 128, 0}));
}
