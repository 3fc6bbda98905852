#include <gtest/gtest.h>

#include <pcl/features/normal_3d.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include <cmath>
#include <random>

#include "cropsight/geometry/knn_normals.hpp"

namespace {
using namespace cropsight::geometry;

std::vector<Eigen::Vector3f> plane_points(int n, std::mt19937& rng) {
  // Tilted plane z = 1 + 0.2 x - 0.1 y, in front of the camera (z forward).
  std::uniform_real_distribution<float> u(-0.5f, 0.5f);
  std::vector<Eigen::Vector3f> pts;
  for (int i = 0; i < n; ++i) {
    const float x = u(rng), y = u(rng);
    pts.emplace_back(x, y, 1.f + 0.2f * x - 0.1f * y);
  }
  return pts;
}

TEST(KnnNormals, PlaneNormalsAreExactAndFaceTheCamera) {
  std::mt19937 rng(1);
  const auto pts = plane_points(2000, rng);
  const auto r = knn_pca(pts);
  const Eigen::Vector3f truth = Eigen::Vector3f(0.2f, -0.1f, -1.f).normalized();  // towards origin
  for (std::size_t i = 0; i < pts.size(); ++i) {
    EXPECT_GT(r.normals[i].dot(truth), 0.9999f) << i;
    EXPECT_NEAR(r.eigenvalues[i][0], 0.f, 1e-9f);
    EXPECT_LE(r.eigenvalues[i][0], r.eigenvalues[i][1]);
    EXPECT_LE(r.eigenvalues[i][1], r.eigenvalues[i][2]);
  }
}

TEST(KnnNormals, SphereNormalsAreRadialAndOrientedToViewpoint) {
  std::mt19937 rng(2);
  std::normal_distribution<float> g;
  const Eigen::Vector3f centre(0, 0, 2);
  const float radius = 0.3f;
  std::vector<Eigen::Vector3f> pts;
  for (int i = 0; i < 5000; ++i) pts.push_back(centre + radius * Eigen::Vector3f(g(rng), g(rng), g(rng)).normalized());
  const auto n = knn_normals(pts);  // viewpoint = origin
  int outward_checked = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Eigen::Vector3f radial = (pts[i] - centre).normalized();
    EXPECT_GT(std::abs(n[i].dot(radial)), 0.99f) << i;
    EXPECT_GE(n[i].dot(-pts[i]), 0.f) << i;  // faces the camera at the origin
    if (radial.z() < -0.5f) {                // front cap: facing the camera = outward
      EXPECT_GT(n[i].dot(radial), 0.99f);
      ++outward_checked;
    }
  }
  EXPECT_GT(outward_checked, 100);
}

TEST(KnnNormals, AgreesWithPclNormalEstimation) {
  std::mt19937 rng(3);
  std::normal_distribution<float> g(0.f, 0.05f);
  std::vector<Eigen::Vector3f> pts;
  for (int i = 0; i < 3000; ++i) pts.emplace_back(g(rng) * 4, g(rng) * 4, 1.f + g(rng) * 0.3f + 0.5f * g(rng) * g(rng));
  const auto ours = knn_normals(pts);
  pcl::PointCloud<pcl::PointXYZ>::Ptr pc(new pcl::PointCloud<pcl::PointXYZ>);
  for (const auto& p : pts) pc->push_back({p.x(), p.y(), p.z()});
  pcl::NormalEstimation<pcl::PointXYZ, pcl::Normal> ne;
  ne.setInputCloud(pc);
  ne.setSearchMethod(pcl::search::KdTree<pcl::PointXYZ>::Ptr(new pcl::search::KdTree<pcl::PointXYZ>));
  ne.setKSearch(30);
  ne.setViewPoint(0, 0, 0);
  pcl::PointCloud<pcl::Normal> pn;
  ne.compute(pn);
  int agree = 0;
  for (std::size_t i = 0; i < pts.size(); ++i)
    if (ours[i].dot(pn[i].getNormalVector3fMap()) > 0.999f) ++agree;
  // Same neighbourhoods and the same PCA; a handful of exact-distance ties may differ.
  EXPECT_GE(agree, int(pts.size()) - 5);
}

TEST(KnnNormals, UnitSphereNormalisation) {
  std::vector<Eigen::Vector3f> pts = {{1, 1, 1}, {3, 1, 1}, {2, 3, 1}, {2, -1, 1}};
  const auto [c, s] = normalize_unit_sphere(pts);
  EXPECT_TRUE(c.isApprox(Eigen::Vector3f(2, 1, 1)));
  EXPECT_FLOAT_EQ(s, 2.f);
  float mx = 0;
  for (const auto& p : pts) mx = std::max(mx, p.norm());
  EXPECT_FLOAT_EQ(mx, 1.f);
}

TEST(PointIndex, KnnRadiusAndNearestMatchBruteForce) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> u(-1, 1);
  std::vector<Eigen::Vector3f> pts;
  for (int i = 0; i < 500; ++i) pts.emplace_back(u(rng), u(rng), u(rng));
  PointIndex index(pts);
  const Eigen::Vector3f q(0.1f, -0.2f, 0.3f);
  std::vector<int> out;
  index.radius(q, 0.4f, out);
  int brute = 0;
  for (const auto& p : pts) brute += (p - q).norm() <= 0.4f;
  EXPECT_EQ(int(out.size()), brute);
  index.knn(q, 5, out);
  ASSERT_EQ(out.size(), 5u);
  EXPECT_EQ(out[0], index.nearest(q));
}
}  // namespace
