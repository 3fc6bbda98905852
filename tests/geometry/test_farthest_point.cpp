#include <gtest/gtest.h>

#include <pcl/filters/farthest_point_sampling.h>
#include <pcl/point_types.h>

#include <random>
#include <set>

#include "cropsight/geometry/farthest_point.hpp"

namespace {
using namespace cropsight::geometry;

TEST(FarthestPoint, MatchesPclFarthestPointSampling) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1, 1);
  std::vector<Eigen::Vector3f> pts;
  pcl::PointCloud<pcl::PointXYZ>::Ptr pc(new pcl::PointCloud<pcl::PointXYZ>);
  for (int i = 0; i < 3000; ++i) {
    pts.emplace_back(u(rng), u(rng), u(rng));
    pc->push_back({pts.back().x(), pts.back().y(), pts.back().z()});
  }
  const unsigned seed = 42;
  pcl::FarthestPointSampling<pcl::PointXYZ> fps;
  fps.setInputCloud(pc);
  fps.setSample(256);
  fps.setSeed(seed);
  pcl::Indices pcl_idx;
  fps.filter(pcl_idx);
  // PCL draws its start point like this; start ours at the same point.
  std::mt19937 gen(seed);
  std::uniform_int_distribution<pcl::index_t> dis(0, pcl::index_t(pts.size()) - 1);
  const std::size_t start = std::size_t(dis(gen));
  const auto ours = farthest_point_sample(pts, 256, start);
  ASSERT_EQ(ours.size(), pcl_idx.size());
  for (std::size_t i = 0; i < ours.size(); ++i) EXPECT_EQ(ours[i], pcl_idx[i]) << i;
}

TEST(FarthestPoint, CoversTheCloudAndHandlesSmallClouds) {
  std::vector<Eigen::Vector3f> pts;
  for (int i = 0; i < 100; ++i) pts.emplace_back(float(i), 0, 0);
  const auto s = farthest_point_sample(pts, 3, 0);
  EXPECT_EQ(s, (std::vector<int>{0, 99, 49}));
  EXPECT_EQ(farthest_point_sample(pts, 200).size(), 100u);
}

TEST(RandomSample, DistinctWhenPossibleAndFixedCount) {
  const auto a = random_sample(1000, 100, 7);
  EXPECT_EQ(std::set<int>(a.begin(), a.end()).size(), 100u);
  EXPECT_EQ(a, random_sample(1000, 100, 7));  // deterministic given the seed
  const auto b = random_sample(10, 25, 7);
  EXPECT_EQ(b.size(), 25u);
  EXPECT_EQ(std::set<int>(b.begin(), b.end()).size(), 10u);
}

TEST(CarryBack, NearestSampleLabels) {
  const std::vector<Eigen::Vector3f> samples = {{0, 0, 0}, {10, 0, 0}};
  const std::vector<Eigen::Vector3f> all = {{1, 0, 0}, {9, 1, 0}, {4.9f, 0, 0}, {5.1f, 0, 0}};
  EXPECT_EQ(carry_labels_back(samples, {3, 7}, all), (std::vector<int>{3, 7, 3, 7}));
}
}  // namespace
