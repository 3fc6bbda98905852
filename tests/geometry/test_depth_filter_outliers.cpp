// Depth-range filter and statistical outlier removal (the latter against
// pcl::StatisticalOutlierRemoval with the same k and multiplier on the same points).
#include <gtest/gtest.h>
#include <pcl/filters/statistical_outlier_removal.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <iostream>
#include <random>

#include "cropsight/core/error.hpp"
#include "cropsight/geometry/depth_filter.hpp"
#include "cropsight/geometry/statistical_outlier.hpp"
#include "geometry/synthetic_scene.hpp"

using namespace cropsight;

TEST(DepthFilter, KeepsInclusiveRangeAndClearsNormals) {
  OrganizedCloud c(4, 1);
  const float zs[4] = {0.4f, 0.5f, 1.0f, 1.2f};
  for (int i = 0; i < 4; ++i) c.x[i] = 0.1f, c.y[i] = 0.2f, c.z[i] = zs[i];
  c.allocate_normals();
  for (int i = 0; i < 4; ++i) c.nx[i] = 0, c.ny[i] = 0, c.nz[i] = -1, c.curvature[i] = 0;
  EXPECT_EQ(geometry::filter_depth_range(c, {}), 2u);
  EXPECT_TRUE(std::isnan(c.z[0]) && std::isnan(c.x[0]) && std::isnan(c.nx[0]));
  EXPECT_FLOAT_EQ(c.z[1], 0.5f);
  EXPECT_FLOAT_EQ(c.z[2], 1.0f);
  EXPECT_TRUE(std::isnan(c.z[3]) && std::isnan(c.curvature[3]));
  EXPECT_EQ(geometry::valid_indices(c), (std::vector<int>{1, 2}));
  EXPECT_THROW(geometry::filter_depth_range(c, {.min_depth = 1.0f, .max_depth = 0.5f}), Error);
}

TEST(StatisticalOutliers, MatchesPclStatisticalOutlierRemoval) {
  auto scene = cropsight::testing::make_synthetic_scene({.width = 160, .height = 132});
  auto& c = scene.cloud;
  // Flying pixels: 150 points pulled towards the camera at random.
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> pix(0, int(c.size()) - 1);
  std::uniform_real_distribution<float> scale(0.6f, 0.95f);
  for (int k = 0; k < 150; ++k) {
    const int i = pix(rng);
    if (!c.valid(i)) continue;
    const float s = scale(rng);
    c.x[i] *= s, c.y[i] *= s, c.z[i] *= s;
  }
  const auto idx = geometry::valid_indices(c);
  const auto kept = geometry::remove_statistical_outliers(c, idx, {});

  auto pc = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  for (int i : idx) pc->push_back(pcl::PointXYZ(c.x[i], c.y[i], c.z[i]));
  pcl::StatisticalOutlierRemoval<pcl::PointXYZ> sor;
  sor.setInputCloud(pc);
  sor.setMeanK(100);
  sor.setStddevMulThresh(1.0);
  pcl::Indices pcl_kept;
  sor.filter(pcl_kept);
  std::vector<int> ref;
  for (int k : pcl_kept) ref.push_back(idx[std::size_t(k)]);

  std::vector<int> diff;
  std::set_symmetric_difference(kept.begin(), kept.end(), ref.begin(), ref.end(), std::back_inserter(diff));
  std::cout << "[SOR vs PCL] points " << idx.size() << ", kept ours " << kept.size() << ", PCL " << ref.size()
            << ", differing " << diff.size() << "\n";
  EXPECT_LT(kept.size(), idx.size());
  EXPECT_LE(diff.size(), idx.size() / 1000);
}

TEST(StatisticalOutliers, RemovesIsolatedPointFromPointList) {
  std::vector<Eigen::Vector3f> pts;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j) pts.emplace_back(0.01f * i, 0.01f * j, 1.0f);
  pts.emplace_back(5.0f, 5.0f, 5.0f);
  const auto kept = geometry::remove_statistical_outliers(pts, {.mean_k = 8, .std_mul = 1.0});
  EXPECT_EQ(std::count(kept.begin(), kept.end(), 400), 0);
  EXPECT_GT(kept.size(), 300u);
  EXPECT_THROW(geometry::remove_statistical_outliers(pts, {.mean_k = 0}), Error);
}
