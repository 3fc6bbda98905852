// Segment growth over unclustered pixels (segment_growth.hpp) on hand-made organised clouds:
// which pixels a segment takes, which it must leave (other segments, gaps, the radius), order.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "cropsight/core/error.hpp"
#include "cropsight/core/organized_cloud.hpp"
#include "cropsight/segmentation/segment_growth.hpp"

using namespace cropsight;
using segmentation::grow_into_free_pixels;
using segmentation::SegmentGrowthOptions;
using segmentation::SegmentGrowthWorkspace;

namespace {
// A w×1 row of points 1 cm apart along x at depth z (NaN where z is NaN).
OrganizedCloud row(const std::vector<float>& z) {
  OrganizedCloud c(int(z.size()), 1);
  for (std::size_t i = 0; i < z.size(); ++i) {
    c.x[i] = 0.01f * float(i);
    c.y[i] = 0.0f;
    c.z[i] = z[i];
  }
  return c;
}
Segment segment(const OrganizedCloud& c, std::vector<int> idx) {
  Segment s;
  s.indices = std::move(idx);
  summarize(s, c);
  return s;
}
}  // namespace

TEST(SegmentGrowth, TakesConnectedFreePixelsAndStopsAtGapsAndOtherSegments) {
  const float nan = std::nanf("");
  // pixels: 0 1 2 | 3 4 (free) | 5 jump 5 cm | 6 free | 7 nan | 8 free
  OrganizedCloud c = row({1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.05f, 1.05f, nan, 1.05f});
  Segment head = segment(c, {1, 2});
  Segment leaf = segment(c, {0});
  std::vector<Segment*> all = {&head, &leaf};
  const std::vector<int> grow = {0};
  SegmentGrowthWorkspace ws;
  // Neighbours 1 cm apart join at 1.5 cm; the 5 cm jump stops the growth at pixel 4; pixel 0
  // belongs to the leaf and is never taken.
  const std::size_t added = grow_into_free_pixels(c, all, grow, {0.015f, 1.0f}, ws);
  EXPECT_EQ(added, 2u);
  EXPECT_EQ(head.indices, (std::vector<int>{1, 2, 3, 4}));
  EXPECT_EQ(leaf.indices, (std::vector<int>{0}));
  EXPECT_EQ(head.box.x, 1);
  EXPECT_EQ(head.box.width, 4);
  EXPECT_NEAR(head.centroid.x(), 0.025f, 1e-6f);
  // A tolerance past the jump takes 5 and 6, and the NaN pixel stops it before 8.
  head = segment(c, {1, 2});
  grow_into_free_pixels(c, all, grow, {0.06f, 1.0f}, ws);
  EXPECT_EQ(head.indices, (std::vector<int>{1, 2, 3, 4, 5, 6}));
}

TEST(SegmentGrowth, RadiusBoundsTheGrowthAroundTheCentroid) {
  OrganizedCloud c = row(std::vector<float>(20, 1.0f));
  Segment s = segment(c, {0, 1, 2});  // centroid x = 1 cm
  std::vector<Segment*> all = {&s};
  SegmentGrowthWorkspace ws;
  grow_into_free_pixels(c, all, std::vector<int>{0}, {0.015f, 0.045f}, ws);
  // Pixels up to x = 5 cm (4 cm from the centroid) join; x = 5.5 cm would be 4.5 cm away.
  EXPECT_EQ(s.indices, (std::vector<int>{0, 1, 2, 3, 4, 5}));
}

TEST(SegmentGrowth, TheFirstSegmentInTheOrderClaimsContestedPixels) {
  OrganizedCloud c = row(std::vector<float>(7, 1.0f));
  Segment a = segment(c, {0}), b = segment(c, {6});
  std::vector<Segment*> all = {&a, &b};
  SegmentGrowthWorkspace ws;
  grow_into_free_pixels(c, all, std::vector<int>{1, 0}, {0.015f, 1.0f}, ws);
  EXPECT_EQ(b.indices, (std::vector<int>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(a.indices, (std::vector<int>{0}));
}

TEST(SegmentGrowth, BadArgumentsAreErrors) {
  OrganizedCloud c = row({1.0f, 1.0f});
  Segment s;
  s.indices = {5};
  std::vector<Segment*> all = {&s};
  SegmentGrowthWorkspace ws;
  EXPECT_THROW(grow_into_free_pixels(c, all, std::vector<int>{0}, {0.01f, 0.1f}, ws), Error);
  s.indices = {0};
  EXPECT_THROW(grow_into_free_pixels(c, all, std::vector<int>{1}, {0.01f, 0.1f}, ws), Error);
  EXPECT_THROW(grow_into_free_pixels(c, all, std::vector<int>{0}, {0.0f, 0.1f}, ws), Error);
  EXPECT_EQ(grow_into_free_pixels(c, all, std::vector<int>{}, {0.0f, 0.1f}, ws), 0u);
}

// The caller's owner map (e.g. the flood fill's labels) gives the same growth as the one built
// from the segments, and records the grown pixels.
TEST(SegmentGrowth, CallersOwnerMapGivesTheSameGrowth) {
  OrganizedCloud c = row({1.0f, 1.0f, 1.0f, 1.0f, std::nanf(""), 1.0f, 1.0f});
  Segment a = segment(c, {0}), b = segment(c, {6});
  std::vector<Segment*> all = {&a, &b};
  SegmentGrowthWorkspace ws;
  grow_into_free_pixels(c, all, std::vector<int>{0, 1}, {0.015f, 1.0f}, ws);
  Segment a2 = segment(c, {0}), b2 = segment(c, {6});
  std::vector<Segment*> all2 = {&a2, &b2};
  std::vector<int> owner = {0, -1, -1, -1, -1, -1, 1}, queue;
  grow_into_free_pixels(c, all2, std::vector<int>{0, 1}, {0.015f, 1.0f}, owner, queue);
  EXPECT_EQ(a2.indices, a.indices);
  EXPECT_EQ(b2.indices, b.indices);
  EXPECT_EQ(a.indices, (std::vector<int>{0, 1, 2, 3}));  // the NaN pixel 4 stops both
  EXPECT_EQ(b.indices, (std::vector<int>{5, 6}));
  EXPECT_EQ(owner, (std::vector<int>{0, 0, 0, 0, -1, 1, 1}));
  std::vector<int> short_map(3, -1);
  EXPECT_THROW(grow_into_free_pixels(c, all2, std::vector<int>{0}, {0.015f, 1.0f}, short_map, queue), Error);
}
