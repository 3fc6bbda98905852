// VFH against pcl::VFHEstimation on the same points and normals (segments of the synthetic
// scene with our integral-image normals).
#include <gtest/gtest.h>
#include <pcl/features/vfh.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include <cmath>
#include <iostream>

#include "cropsight/features/vfh.hpp"
#include "cropsight/geometry/integral_normals.hpp"
#include "geometry/synthetic_scene.hpp"

using namespace cropsight;

namespace {

std::vector<float> pcl_vfh(const OrganizedCloud& c, const std::vector<int>& idx, const features::VfhConfig& cfg) {
  auto pts = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  auto nrm = pcl::make_shared<pcl::PointCloud<pcl::Normal>>();
  for (int i : idx) {
    pts->push_back(pcl::PointXYZ(c.x[i], c.y[i], c.z[i]));
    nrm->push_back(pcl::Normal(c.nx[i], c.ny[i], c.nz[i], c.curvature[i]));
  }
  pcl::VFHEstimation<pcl::PointXYZ, pcl::Normal, pcl::VFHSignature308> vfh;
  vfh.setInputCloud(pts);
  vfh.setInputNormals(nrm);
  vfh.setSearchMethod(pcl::make_shared<pcl::search::KdTree<pcl::PointXYZ>>());
  vfh.setNormalizeBins(cfg.normalize_bins);
  vfh.setNormalizeDistance(cfg.normalize_distances);
  vfh.setFillSizeComponent(cfg.size_component);
  pcl::PointCloud<pcl::VFHSignature308> out;
  vfh.compute(out);
  return std::vector<float>(out[0].histogram, out[0].histogram + 308);
}

// Points of one scene label that have a normal.
std::vector<int> label_points(const OrganizedCloud& c, int label) {
  std::vector<int> idx;
  for (std::size_t i = 0; i < c.size(); ++i)
    if (c.labels[i] == label && std::isfinite(c.nx[i])) idx.push_back(int(i));
  return idx;
}

}  // namespace

TEST(Vfh, MatchesPclVfhEstimation) {
  auto scene = cropsight::testing::make_synthetic_scene();
  geometry::estimate_normals_integral(scene.cloud);
  const features::VfhConfig configs[] = {
      {},
      {.normalize_bins = true, .normalize_distances = true, .size_component = true},
      {.normalize_bins = false, .normalize_distances = false, .size_component = true}};
  double worst_rel = 0;
  for (const auto& cfg : configs) {
    for (int label : {1, 2, 3, 100, 0}) {
      const auto idx = label_points(scene.cloud, label);
      ASSERT_GT(idx.size(), 500u);
      const auto ours = features::compute_vfh(scene.cloud, idx, cfg);
      const auto ref = pcl_vfh(scene.cloud, idx, cfg);
      double l1 = 0, mass = 0;
      for (int b = 0; b < features::kVfhBins; ++b) l1 += std::abs(double(ours[b]) - ref[b]), mass += ref[b];
      const double rel = l1 / mass;
      worst_rel = std::max(worst_rel, rel);
      std::cout << "[VFH vs PCL] label " << label << " points " << idx.size() << " size_component "
                << cfg.size_component << ": L1 " << l1 << " (histogram mass " << mass << ", relative " << rel << ")\n";
      EXPECT_LT(rel, 1e-3) << "label " << label;
    }
  }
  std::cout << "[VFH vs PCL] worst relative L1 " << worst_rel << "\n";
}

TEST(Vfh, DefaultLayoutAndNormalisation) {
  auto scene = cropsight::testing::make_synthetic_scene({.width = 256, .height = 212});
  geometry::estimate_normals_integral(scene.cloud);
  const auto idx = label_points(scene.cloud, 1);
  ASSERT_GT(idx.size(), 100u);
  const auto h = features::compute_vfh(scene.cloud, idx);
  const double n = double(idx.size());
  double f1 = 0, f4 = 0, vp = 0;
  for (int b = 0; b < 45; ++b) f1 += h[b];
  for (int b = 135; b < 180; ++b) f4 += h[b];
  for (int b = 180; b < 308; ++b) vp += h[b];
  EXPECT_NEAR(f1, 100.0 * n / (n - 1), 1e-2);  // every pair counted, 100/(N-1) each
  EXPECT_EQ(f4, 0.0);                          // PCL default: no size component
  EXPECT_NEAR(vp, 100.0, 1e-2);
  // Fewer than two usable points: zeros.
  const std::vector<int> one = {idx[0]};
  const auto z = features::compute_vfh(scene.cloud, one);
  for (float v : z) EXPECT_EQ(v, 0.0f);
}
