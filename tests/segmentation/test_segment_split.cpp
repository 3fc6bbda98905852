// Splitting segments along barrier pixels (segment_split.hpp) on hand-made organised clouds.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "cropsight/core/error.hpp"
#include "cropsight/core/organized_cloud.hpp"
#include "cropsight/segmentation/segment_split.hpp"

using namespace cropsight;
using segmentation::SegmentSplitWorkspace;
using segmentation::split_segments;

namespace {
constexpr int kW = 10, kH = 4;
// A kW×kH plane at 1 m, points 1 cm apart.
OrganizedCloud plane() {
  OrganizedCloud c(kW, kH);
  for (int v = 0; v < kH; ++v)
    for (int u = 0; u < kW; ++u) {
      const std::size_t i = std::size_t(v * kW + u);
      c.x[i] = 0.01f * float(u), c.y[i] = 0.01f * float(v), c.z[i] = 1.0f;
    }
  return c;
}
Segment of(const OrganizedCloud& c, const std::vector<int>& idx) {
  Segment s;
  s.indices = idx;
  summarize(s, c);
  return s;
}
std::vector<int> columns(int from, int to) {  // pixels of columns [from, to), ascending
  std::vector<int> out;
  for (int v = 0; v < kH; ++v)
    for (int u = from; u < to; ++u) out.push_back(v * kW + u);
  std::sort(out.begin(), out.end());
  return out;
}
}  // namespace

TEST(SegmentSplit, CutsATargetAlongItsBarrierAndLeavesTheOthers) {
  const OrganizedCloud c = plane();
  const Segment left = of(c, columns(0, 8)), right = of(c, columns(8, 10));
  const std::vector<const Segment*> segs = {&left, &right};
  std::vector<std::uint8_t> barrier(c.size(), 0);
  for (int v = 0; v < kH; ++v) barrier[std::size_t(v * kW + 3)] = 1;  // column 3 cuts `left` into 3 + 4 columns
  SegmentSplitWorkspace ws;
  const std::vector<int> targets = {0};
  const auto pieces = split_segments(c, segs, targets, barrier, 0.015f, 4, 100, ws);
  ASSERT_EQ(pieces.size(), 2u);
  EXPECT_EQ(pieces[0].parent, 0);
  EXPECT_EQ(pieces[1].parent, 0);
  EXPECT_EQ(pieces[0].segment.indices, columns(0, 3));  // ascending, raster order of first pixel
  EXPECT_EQ(pieces[1].segment.indices, columns(4, 8));
  EXPECT_EQ(pieces[1].segment.box.x, 4);
  EXPECT_NEAR(pieces[1].segment.centroid.x(), 0.055f, 1e-6f);
  EXPECT_TRUE(std::all_of(ws.owner.begin(), ws.owner.end(), [](int o) { return o == -1; }))
      << "the workspace is clean for the next call";

  // The size range drops the 12-point piece; a second call with the same workspace agrees.
  const auto big = split_segments(c, segs, targets, barrier, 0.015f, 13, 100, ws);
  ASSERT_EQ(big.size(), 1u);
  EXPECT_EQ(big[0].segment.indices, columns(4, 8));
  // Both targets: `right` has no barrier pixel and comes back whole.
  const std::vector<int> both = {0, 1};
  const auto all = split_segments(c, segs, both, barrier, 0.015f, 1, 100, ws);
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[2].parent, 1);
  EXPECT_EQ(all[2].segment.indices, right.indices);
}

TEST(SegmentSplit, NeighboursJoinOnlyWithinOneTargetAndTheTolerance) {
  OrganizedCloud c = plane();
  for (int v = 0; v < kH; ++v) c.z[std::size_t(v * kW + 5)] = c.z[std::size_t(v * kW + 6)] = 1.05f;  // a 5 cm step
  const Segment a = of(c, columns(0, 5)), b = of(c, columns(5, 10));
  const std::vector<const Segment*> segs = {&a, &b};
  const std::vector<std::uint8_t> none(c.size(), 0);
  SegmentSplitWorkspace ws;
  const std::vector<int> both = {0, 1};
  const auto pieces = split_segments(c, segs, both, none, 0.015f, 1, 100, ws);
  // a: whole (its pixels touch b's but never join them); b: columns 5-6 and 7-9 parted by the step.
  ASSERT_EQ(pieces.size(), 3u);
  EXPECT_EQ(pieces[0].segment.indices, a.indices);
  EXPECT_EQ(pieces[1].segment.indices, columns(5, 7));
  EXPECT_EQ(pieces[2].segment.indices, columns(7, 10));
  EXPECT_EQ(pieces[2].parent, 1);
}

TEST(SegmentSplit, RejectsBadInput) {
  const OrganizedCloud c = plane();
  const Segment a = of(c, columns(0, 5));
  Segment bad;
  bad.indices = {int(c.size())};
  const std::vector<const Segment*> segs = {&a, &bad};
  const std::vector<std::uint8_t> none(c.size(), 0), short_barrier(3, 0);
  SegmentSplitWorkspace ws;
  const std::vector<int> t0 = {0}, t1 = {1}, t2 = {2};
  EXPECT_THROW(split_segments(c, segs, t0, short_barrier, 0.015f, 1, 10, ws), Error);
  EXPECT_THROW(split_segments(c, segs, t0, none, 0.0f, 1, 10, ws), Error);
  EXPECT_THROW(split_segments(c, segs, t0, none, 0.015f, 5, 4, ws), Error);
  EXPECT_THROW(split_segments(c, segs, t1, none, 0.015f, 1, 10, ws), Error);
  EXPECT_THROW(split_segments(c, segs, t2, none, 0.015f, 1, 10, ws), Error);
}
