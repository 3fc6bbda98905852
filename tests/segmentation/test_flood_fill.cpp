// The organised flood fill on hand-made grids: exact expected labels, size range, predicates.
#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "cropsight/core/error.hpp"
#include "cropsight/segmentation/flood_fill.hpp"
#include "cropsight/segmentation/organized_clustering.hpp"

using namespace cropsight;
using segmentation::flood_fill;
using segmentation::FloodFillWorkspace;

namespace {
// Pixels with the same non-zero value form one region; value 9 joins any neighbour region but
// never grows it (and never seeds).
struct GridPredicate {
  const std::vector<int>& g;
  bool member(int q) const { return g[q] != 0; }
  bool seed(int s) const { return member(s) && expands(s); }
  bool expands(int p) const { return g[p] != 9; }
  bool similar(int p, int q) const { return g[q] == 9 || g[p] == g[q]; }
};
}  // namespace

TEST(FloodFill, LabelsFourConnectedRegionsInRasterOrder) {
  const std::vector<int> g = {1, 1, 0, 2,  //
                              1, 0, 0, 2,  //
                              0, 0, 3, 3,  //
                              4, 0, 3, 0};
  FloodFillWorkspace ws;
  const auto segs = flood_fill(4, 4, GridPredicate{g}, 1, 100, ws);
  ASSERT_EQ(segs.size(), 4u);
  const std::vector<int> expect = {0,  0,  -1, 1,  //
                                   0,  -1, -1, 1,  //
                                   -1, -1, 2,  2,  //
                                   3,  -1, 2,  -1};
  EXPECT_EQ(ws.labels, expect);
  EXPECT_EQ(segs[0].indices, (std::vector<int>{0, 1, 4}));  // ascending (raster order)
  EXPECT_EQ(segs[3].indices, (std::vector<int>{12}));
}

TEST(FloodFill, SizeRangeDropsSegmentsAndTheirLabels) {
  const std::vector<int> g = {1, 1, 0, 2,  //
                              1, 0, 0, 2,  //
                              0, 0, 3, 3,  //
                              4, 0, 3, 0};
  FloodFillWorkspace ws;
  auto segs = flood_fill(4, 4, GridPredicate{g}, 2, 2, ws);  // only the 2-pixel region
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_EQ(segs[0].indices, (std::vector<int>{3, 7}));
  const std::vector<int> expect = {-1, -1, -1, 0,   //
                                   -1, -1, -1, 0,   //
                                   -1, -1, -1, -1,  //
                                   -1, -1, -1, -1};
  EXPECT_EQ(ws.labels, expect);
  segs = flood_fill(4, 4, GridPredicate{g}, 3, 3, ws);
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_EQ(ws.labels[0], 0);
  EXPECT_EQ(ws.labels[10], 1);
  EXPECT_THROW(flood_fill(4, 4, GridPredicate{g}, 3, 2, ws), Error);
  EXPECT_THROW(flood_fill(4, 4, GridPredicate{g}, 0, 2, ws), Error);
}

TEST(FloodFill, DiagonalPixelsAreNotConnectedAndRowsDoNotWrap) {
  const std::vector<int> g = {1, 0, 1,  //
                              0, 1, 0,  //
                              1, 0, 0};
  FloodFillWorkspace ws;
  EXPECT_EQ(flood_fill(3, 3, GridPredicate{g}, 1, 9, ws).size(), 4u);
  // Pixel 2 (end of row 0) and pixel 3 (start of row 1) are adjacent in memory, not on the grid.
  const std::vector<int> h = {0, 0, 1,  //
                              1, 0, 0};
  EXPECT_EQ(flood_fill(3, 2, GridPredicate{h}, 1, 9, ws).size(), 2u);
}

TEST(FloodFill, NonExpandingPixelsAreAbsorbedButDoNotGrow) {
  // 1 9 1: the 9 joins the left region but does not pass it on to the right 1.
  const std::vector<int> g = {1, 9, 1};
  FloodFillWorkspace ws;
  const auto segs = flood_fill(3, 1, GridPredicate{g}, 1, 9, ws);
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_EQ(segs[0].indices, (std::vector<int>{0, 1}));
  EXPECT_EQ(segs[1].indices, (std::vector<int>{2}));
  // A lone 9 never seeds.
  const std::vector<int> lone = {9, 0, 1};
  EXPECT_EQ(flood_fill(3, 1, GridPredicate{lone}, 1, 9, ws).size(), 1u);
  EXPECT_EQ(ws.labels[0], -1);
}

TEST(OesPredicate, EdgesAreBarriersAndDistanceSplits) {
  // 5×1 row: points 1 mm apart except a 5 cm gap between 3 and 4; pixel 1 is an edge.
  OrganizedCloud c(5, 1);
  const float xs[5] = {0.000f, 0.001f, 0.002f, 0.003f, 0.053f};
  for (int i = 0; i < 5; ++i) c.x[i] = xs[i], c.y[i] = 0, c.z[i] = 0.8f;
  const std::vector<std::uint8_t> edges = {0, 2, 0, 0, 0};
  segmentation::OrganizedClusteringWorkspace ws;
  auto segs = segmentation::segment_oes(
      c, edges, {.distance_tolerance = 0.01f, .barrier_labels = 7, .min_size = 1, .max_size = 10}, ws);
  ASSERT_EQ(segs.size(), 3u);  // {0}, {2,3}, {4}
  EXPECT_EQ(ws.labels, (std::vector<int>{0, -1, 1, 1, 2}));
  EXPECT_FLOAT_EQ(segs[1].centroid.x(), 0.0025f);
  EXPECT_EQ(segs[1].box, (Box2D{2, 0, 2, 1}));
  // Without occluding edges as barriers, pixel 1 links 0..3.
  segs = segmentation::segment_oes(
      c, edges, {.distance_tolerance = 0.01f, .barrier_labels = 4, .min_size = 1, .max_size = 10}, ws);
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_EQ(segs[0].size(), 4u);
  EXPECT_THROW(segmentation::segment_oes(c, std::vector<std::uint8_t>(3), {}, ws), Error);
}

TEST(OesPredicate, BorderSegmentsMayUseASmallerMinimum) {
  // 10×6 grid, NaN except two 2×3 patches (6 points): one on the left border, one inside.
  OrganizedCloud c(10, 6);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (std::size_t i = 0; i < c.size(); ++i) c.x[i] = c.y[i] = c.z[i] = nan;
  auto set = [&c](int u, int v) {
    const std::size_t i = std::size_t(v) * 10 + u;
    c.x[i] = 0.001f * u, c.y[i] = 0.001f * v, c.z[i] = 0.8f;
  };
  for (int v = 1; v < 4; ++v)
    for (int u : {0, 1, 5, 6}) set(u, v);
  const std::vector<std::uint8_t> edges(c.size(), 0);
  segmentation::OrganizedClusteringWorkspace ws;
  segmentation::OesConfig cfg{.distance_tolerance = 0.01f, .barrier_labels = 0, .min_size = 7, .max_size = 100};
  EXPECT_TRUE(segmentation::segment_oes(c, edges, cfg, ws).empty());
  cfg.min_size_border = 6;
  const auto segs = segmentation::segment_oes(c, edges, cfg, ws);
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_EQ(segs[0].box, (Box2D{0, 1, 2, 3}));
  EXPECT_EQ(ws.labels[std::size_t(1 * 10 + 5)], -1);
  cfg.min_size = 6;  // both kept once the interior minimum allows it
  EXPECT_EQ(segmentation::segment_oes(c, edges, cfg, ws).size(), 2u);
  cfg.min_size_border = -1;
  EXPECT_THROW(segmentation::segment_oes(c, edges, cfg, ws), Error);
}

TEST(OrgPredicate, NormalAngleAndCurvatureRule) {
  // 6×1 row, planar positions; normals turn by 2° per pixel except a 20° kink between 2 and 3;
  // pixel 5 has high curvature.
  OrganizedCloud c(6, 1);
  c.allocate_normals();
  const float deg[6] = {0, 2, 4, 24, 26, 28};
  for (int i = 0; i < 6; ++i) {
    c.x[i] = 0.002f * i, c.y[i] = 0, c.z[i] = 0.8f;
    const float a = deg[i] * float(M_PI) / 180.0f;
    c.nx[i] = std::sin(a), c.ny[i] = 0, c.nz[i] = -std::cos(a);
    c.curvature[i] = i == 5 ? 0.2f : 0.01f;
  }
  segmentation::OrganizedClusteringWorkspace ws;
  const segmentation::OrgConfig cfg{.angle_threshold = 5.0f * float(M_PI) / 180.0f,
                                    .curvature_threshold = 0.05f,
                                    .distance_tolerance = 0.01f,
                                    .min_size = 1,
                                    .max_size = 10};
  auto segs = segmentation::segment_org(c, cfg, ws);
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_EQ(ws.labels, (std::vector<int>{0, 0, 0, 1, 1, 1}));  // 5 is absorbed, not a seed
  // If the high-curvature pixel sits between two regions, it stops the growth.
  c.curvature[5] = 0.01f;
  c.curvature[4] = 0.2f;
  c.nx[5] = std::sin(26.5f * float(M_PI) / 180.0f), c.nz[5] = -std::cos(26.5f * float(M_PI) / 180.0f);
  segs = segmentation::segment_org(c, cfg, ws);
  EXPECT_EQ(ws.labels, (std::vector<int>{0, 0, 0, 1, 1, 2}));
  OrganizedCloud no_normals(6, 1);
  EXPECT_THROW(segmentation::segment_org(no_normals, cfg, ws), Error);
}

TEST(FloodFill, IndicesAscendAndSummaryMatchesSummarize) {
  // A U-shaped region filled from its top-left seed: breadth-first order would visit the two
  // arms alternately; the returned indices are ascending, and flood_fill_segments' summary is
  // the one summarize() gives.
  const std::vector<int> g = {1, 0, 1, 0,  //
                              1, 0, 1, 0,  //
                              1, 1, 1, 0,  //
                              0, 0, 0, 2};
  OrganizedCloud c(4, 4);
  for (int i = 0; i < 16; ++i)
    c.x[i] = 0.01f * float(i % 4), c.y[i] = 0.013f * float(i / 4), c.z[i] = 0.8f + 0.001f * float(i);
  FloodFillWorkspace ws;
  const auto segs = segmentation::flood_fill_segments(c, GridPredicate{g}, 1, 100, ws);
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_EQ(segs[0].indices, (std::vector<int>{0, 2, 4, 6, 8, 9, 10}));
  EXPECT_EQ(segs[1].indices, (std::vector<int>{15}));
  for (const auto& s : segs) {
    Segment ref;
    ref.indices = s.indices;
    summarize(ref, c);
    EXPECT_EQ(s.centroid, ref.centroid);
    EXPECT_EQ(s.min, ref.min);
    EXPECT_EQ(s.max, ref.max);
    EXPECT_EQ(s.box, ref.box);
  }
  EXPECT_EQ(segs[0].box, (Box2D{0, 0, 3, 3}));
}
