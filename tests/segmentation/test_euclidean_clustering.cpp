// Euclidean clustering against pcl::EuclideanClusterExtraction: the same clusters up to order.
#include <gtest/gtest.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/extract_clusters.h>

#include <algorithm>
#include <iostream>
#include <set>

#include "cropsight/core/error.hpp"
#include "cropsight/geometry/depth_filter.hpp"
#include "cropsight/segmentation/euclidean_clustering.hpp"
#include "geometry/synthetic_scene.hpp"

using namespace cropsight;

TEST(EuclideanClustering, SameClustersAsPcl) {
  auto scene = cropsight::testing::make_synthetic_scene({.width = 256, .height = 212});
  const auto idx = geometry::valid_indices(scene.cloud);
  for (float tol : {0.005f, 0.006f, 0.008f}) {
    const segmentation::EuclideanClusterConfig cfg{.tolerance = tol, .min_size = 50, .max_size = 60000};
    const auto ours = segmentation::euclidean_clusters(scene.cloud, idx, cfg);

    auto pc = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
    for (int i : idx) pc->push_back(pcl::PointXYZ(scene.cloud.x[i], scene.cloud.y[i], scene.cloud.z[i]));
    pcl::EuclideanClusterExtraction<pcl::PointXYZ> ec;
    ec.setClusterTolerance(tol);
    ec.setMinClusterSize(cfg.min_size);
    ec.setMaxClusterSize(cfg.max_size);
    ec.setSearchMethod(pcl::make_shared<pcl::search::KdTree<pcl::PointXYZ>>());
    ec.setInputCloud(pc);
    std::vector<pcl::PointIndices> ref;
    ec.extract(ref);

    std::set<std::vector<int>> a, b;
    for (const auto& s : ours) a.insert(s.indices);
    for (const auto& r : ref) {
      std::vector<int> v;
      for (int k : r.indices) v.push_back(idx[std::size_t(k)]);
      std::sort(v.begin(), v.end());
      b.insert(v);
    }
    std::cout << "[FEC vs PCL, tol " << tol << "] clusters ours " << a.size() << ", PCL " << b.size() << "\n";
    EXPECT_GT(a.size(), 1u);
    EXPECT_EQ(a, b);
  }
}

TEST(EuclideanClustering, PointListAndSizeRange) {
  std::vector<Eigen::Vector3f> pts;
  for (int i = 0; i < 10; ++i) pts.emplace_back(0.001f * i, 0, 1);     // chain of 10, 1 mm apart
  for (int i = 0; i < 3; ++i) pts.emplace_back(1 + 0.001f * i, 0, 1);  // chain of 3
  pts.emplace_back(5, 5, 5);                                           // singleton
  auto segs = segmentation::euclidean_clusters(pts, {.tolerance = 0.0015f, .min_size = 1, .max_size = 100});
  ASSERT_EQ(segs.size(), 3u);
  segs = segmentation::euclidean_clusters(pts, {.tolerance = 0.0015f, .min_size = 2, .max_size = 5});
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_EQ(segs[0].indices, (std::vector<int>{10, 11, 12}));
  EXPECT_THROW(segmentation::euclidean_clusters(pts, {.tolerance = 0.0f}), Error);
  OrganizedCloud c(2, 1);
  EXPECT_THROW(segmentation::euclidean_clusters(c, {0}, {}), Error);  // index of a NaN point
}
