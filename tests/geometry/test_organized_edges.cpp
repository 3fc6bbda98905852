// Organised edges against pcl::OrganizedEdgeBase on the same synthetic organised cloud.
#include <gtest/gtest.h>
#include <pcl/features/organized_edge_detection.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <cmath>
#include <iostream>

#include "cropsight/core/error.hpp"
#include "cropsight/core/pcl_conversions.hpp"
#include "cropsight/geometry/organized_edges.hpp"
#include "geometry/synthetic_scene.hpp"

using namespace cropsight;

namespace {
struct EdgeAgreement {
  std::size_t agree = 0, total = 0, edges_ours = 0, edges_pcl = 0, edges_agree = 0;
  std::size_t count[8] = {};
};

EdgeAgreement compare(const OrganizedCloud& cloud, const geometry::OrganizedEdgeConfig& cfg) {
  std::vector<std::uint8_t> ours;
  geometry::detect_organized_edges(cloud, cfg, ours);
  auto pc = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  to_pcl(cloud, *pc);
  pcl::OrganizedEdgeBase<pcl::PointXYZ, pcl::Label> oed;
  oed.setInputCloud(pc);
  oed.setDepthDisconThreshold(cfg.depth_discontinuity);
  oed.setMaxSearchNeighbors(cfg.max_search_neighbors);
  pcl::PointCloud<pcl::Label> labels;
  std::vector<pcl::PointIndices> label_indices;
  oed.compute(labels, label_indices);
  EdgeAgreement a;
  a.total = cloud.size();
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const unsigned ref = labels[i].label;
    a.agree += ours[i] == ref;
    a.edges_ours += ours[i] != 0;
    a.edges_pcl += ref != 0;
    a.edges_agree += ours[i] != 0 && ours[i] == ref;
    if (ours[i] < 8) ++a.count[ours[i]];
  }
  return a;
}
}  // namespace

TEST(OrganizedEdges, MatchesPclOnSyntheticScene) {
  auto scene = cropsight::testing::make_synthetic_scene();
  // A hole that touches the image border so that NaN-boundary edges occur too.
  for (int v = 0; v < 60; ++v)
    for (int u = 0; u < 40; ++u) scene.cloud.z[scene.cloud.index(u, v)] = NAN;
  for (std::size_t i = 0; i < scene.cloud.size(); ++i)
    if (std::isnan(scene.cloud.z[i])) scene.cloud.x[i] = scene.cloud.y[i] = NAN;
  const auto a = compare(scene.cloud, {});
  const double agreement = double(a.agree) / double(a.total);
  std::cout << "[edges vs PCL] label agreement " << agreement * 100 << " % of " << a.total
            << " pixels; edge pixels ours " << a.edges_ours << ", PCL " << a.edges_pcl << ", identical "
            << a.edges_agree << "; nan-boundary " << a.count[1] << ", occluding " << a.count[2] << ", occluded "
            << a.count[4] << "\n";
  EXPECT_GE(agreement, 0.99);
  EXPECT_GE(double(a.edges_agree), 0.99 * double(a.edges_pcl));
  EXPECT_GT(a.count[geometry::kEdgeOccluding], 100u);
  EXPECT_GT(a.count[geometry::kEdgeOccluded], 100u);
  EXPECT_GT(a.count[geometry::kEdgeNanBoundary], 10u);
}

// Without the depth labels (the OES presets use only NaN boundaries as barriers) a cheaper row
// pass skips the depth differences: the NaN-boundary pixels must be exactly those of the full run.
TEST(OrganizedEdges, NanBoundaryAloneEqualsItsBitInTheFullRun) {
  auto scene = cropsight::testing::make_synthetic_scene();
  for (int v = 0; v < 60; ++v)
    for (int u = 0; u < 40; ++u) scene.cloud.z[scene.cloud.index(u, v)] = NAN;
  for (int v = 150; v < 170; ++v)  // an inner hole, crossed by the walk
    for (int u = 200; u < 230; ++u) scene.cloud.z[scene.cloud.index(u, v)] = NAN;
  for (std::size_t i = 0; i < scene.cloud.size(); ++i)
    if (std::isnan(scene.cloud.z[i])) scene.cloud.x[i] = scene.cloud.y[i] = NAN;
  const auto full = geometry::detect_organized_edges(scene.cloud, {});
  geometry::OrganizedEdgeConfig nan_only;
  nan_only.detect_occluding = nan_only.detect_occluded = false;
  const auto only = geometry::detect_organized_edges(scene.cloud, nan_only);
  ASSERT_EQ(only.size(), full.size());
  std::size_t nan_pixels = 0, mismatches = 0;
  for (std::size_t i = 0; i < full.size(); ++i) {
    nan_pixels += only[i] == geometry::kEdgeNanBoundary;
    mismatches += only[i] != (full[i] & geometry::kEdgeNanBoundary);
  }
  EXPECT_EQ(mismatches, 0u);
  EXPECT_GT(nan_pixels, 10u);
}

TEST(OrganizedEdges, MatchesPclWithOtherThreshold) {
  const auto scene = cropsight::testing::make_synthetic_scene({.width = 256, .height = 212});
  const auto a = compare(scene.cloud, {.depth_discontinuity = 0.01f, .max_search_neighbors = 20});
  EXPECT_GE(double(a.agree) / double(a.total), 0.99);
  EXPECT_GE(double(a.edges_agree), 0.99 * double(a.edges_pcl));
}

TEST(OrganizedEdges, StepGivesOccludingInFrontOccludedBehind) {
  // Two flat strips: left half at 0.6 m, right half at 0.9 m.
  OrganizedCloud c(10, 5);
  for (int v = 0; v < 5; ++v)
    for (int u = 0; u < 10; ++u) {
      const int i = c.index(u, v);
      c.z[i] = u < 5 ? 0.6f : 0.9f;
      c.x[i] = 0.001f * u, c.y[i] = 0.001f * v;
    }
  const auto labels = geometry::detect_organized_edges(c);
  for (int v = 1; v < 4; ++v) {
    EXPECT_EQ(labels[c.index(4, v)], geometry::kEdgeOccluding);
    EXPECT_EQ(labels[c.index(5, v)], geometry::kEdgeOccluded);
    EXPECT_EQ(labels[c.index(2, v)], geometry::kEdgeNone);
    EXPECT_EQ(labels[c.index(7, v)], geometry::kEdgeNone);
  }
  EXPECT_EQ(labels[c.index(4, 0)], geometry::kEdgeNone);  // border rows are not examined (PCL)
  // Disabling a type removes its labels only.
  const auto only_occluding = geometry::detect_organized_edges(c, {.detect_occluded = false});
  EXPECT_EQ(only_occluding[c.index(4, 2)], geometry::kEdgeOccluding);
  EXPECT_EQ(only_occluding[c.index(5, 2)], geometry::kEdgeNone);
}

TEST(OrganizedEdges, HighCurvatureBitIsOptional) {
  OrganizedCloud c(5, 5);
  for (std::size_t i = 0; i < c.size(); ++i)
    c.x[i] = 0.001f * float(i % 5), c.y[i] = 0.001f * float(i / 5), c.z[i] = 0.8f;
  c.allocate_normals();
  c.curvature[c.index(2, 2)] = 0.1f;
  c.curvature[c.index(1, 2)] = 0.01f;
  EXPECT_EQ(geometry::detect_organized_edges(c)[c.index(2, 2)], geometry::kEdgeNone);  // off by default
  const auto l = geometry::detect_organized_edges(c, {.high_curvature_threshold = 0.05f});
  EXPECT_EQ(l[c.index(2, 2)], geometry::kEdgeHighCurvature);
  EXPECT_EQ(l[c.index(1, 2)], geometry::kEdgeNone);
  EXPECT_EQ(std::count(l.begin(), l.end(), geometry::kEdgeHighCurvature), 1);
}

TEST(OrganizedEdges, RejectsBadConfig) {
  OrganizedCloud c(4, 4);
  EXPECT_THROW(geometry::detect_organized_edges(c, {.depth_discontinuity = -0.1f}), Error);
  EXPECT_THROW(geometry::detect_organized_edges(c, {.max_search_neighbors = -1}), Error);
}
