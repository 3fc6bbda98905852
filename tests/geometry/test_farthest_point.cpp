#include <gtest/gtest.h>

#include <pcl/filters/farthest_point_sampling.h>
#include <pcl/point_types.h>

#include <limits>
#include <random>
#include <set>

#include "cropsight/geometry/farthest_point.hpp"
#include "geometry/farthest_point_step.hpp"

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

// The sampling loop as it was before the three-plane kernel (Eigen's norm, one point at a time):
// the reference the kernel must reproduce index for index.
std::vector<int> fps_reference(const std::vector<Eigen::Vector3f>& points, std::size_t count, std::size_t start) {
  std::vector<float> dist(points.size(), std::numeric_limits<float>::max());
  std::vector<int> out = {int(start)};
  std::size_t cur = start;
  dist[cur] = -1.f;
  while (out.size() < count) {
    const Eigen::Vector3f c = points[cur];
    std::size_t best = 0;
    float best_d = -2.f;
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (dist[i] < 0) continue;
      const float d = std::min(dist[i], (points[i] - c).norm());
      dist[i] = d;
      if (d > best_d) best_d = d, best = i;
    }
    cur = best;
    dist[cur] = -1.f;
    out.push_back(int(cur));
  }
  return out;
}

// Unit-sphere-sized random points, a grid (many equal distances: ties), and duplicated points
// (the grape clouds hold many points at one position), at sizes that leave a tail after the
// eight-point blocks.
std::vector<std::vector<Eigen::Vector3f>> fps_clouds() {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-0.5f, 0.5f);
  std::vector<std::vector<Eigen::Vector3f>> clouds(3);
  for (int i = 0; i < 2051; ++i) clouds[0].emplace_back(u(rng), u(rng), u(rng));
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 9; ++j)
      for (int k = 0; k < 7; ++k) clouds[1].emplace_back(float(i), float(j), float(k) * 0.5f);
  for (int i = 0; i < 517; ++i) clouds[2].push_back(i % 3 == 0 ? Eigen::Vector3f(0.1f, 0.2f, 0.3f) : clouds[0][i]);
  return clouds;
}

TEST(FarthestPoint, ThreePlaneKernelReproducesTheScalarLoop) {
  for (const auto& pts : fps_clouds()) {
    for (std::size_t count : {std::size_t(1), std::size_t(17), pts.size() / 4, pts.size() - 1}) {
      const auto ref = fps_reference(pts, count, 3);
      EXPECT_EQ(farthest_point_sample(pts, count, 3), ref) << pts.size() << " points, " << count;
    }
  }
}

TEST(FarthestPoint, StepAvx2AndBaselineAgreeBitForBit) {
  for (const auto& pts : fps_clouds()) {
    const std::size_t n = pts.size();
    std::vector<float> x(n), y(n), z(n);
    for (std::size_t i = 0; i < n; ++i) x[i] = pts[i].x(), y[i] = pts[i].y(), z[i] = pts[i].z();
    std::vector<float> a(n, std::numeric_limits<float>::max()), b = a;
    a[5] = b[5] = -1.f;
    std::size_t cur = 5;
    for (int step = 0; step < 40; ++step) {
      const std::size_t ia = cropsight::geometry::detail::farthest_point_step(x.data(), y.data(), z.data(), a.data(), n,
                                                                              x[cur], y[cur], z[cur]);
      const std::size_t ib = cropsight::geometry::detail::farthest_point_step(x.data(), y.data(), z.data(), b.data(), n,
                                                                              x[cur], y[cur], z[cur], false);
      ASSERT_EQ(ia, ib) << step;
      for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(a[i], b[i]) << i;  // same floats, not just close
      for (std::size_t i = 0; i < n; ++i) {
        if (b[i] >= 0) {
          ASSERT_LE(b[i], (pts[i] - pts[cur]).norm()) << i;
        }
      }
      cur = ia;
      a[cur] = b[cur] = -1.f;
    }
  }
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
