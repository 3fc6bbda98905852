// Integral-image normals against pcl::IntegralImageNormalEstimation (COVARIANCE_MATRIX, the same
// depth-change factor and smoothing size) on the same synthetic 512×424 organised cloud.
#include <gtest/gtest.h>
#include <pcl/features/integral_image_normal.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <utility>

#include "cropsight/core/error.hpp"
#include "cropsight/core/pcl_conversions.hpp"
#include "cropsight/geometry/integral_normals.hpp"
#include "geometry/synthetic_scene.hpp"

using namespace cropsight;

namespace {

struct Comparison {
  std::size_t both = 0, only_ours = 0, only_pcl = 0, neither = 0;
  double median_deg = 0, p95_deg = 0, median_curv_abs = 0;
};

Comparison compare_with_pcl(const OrganizedCloud& input, const geometry::IntegralNormalConfig& cfg) {
  OrganizedCloud ours = input;
  geometry::IntegralNormalEstimator est(cfg);
  est.compute(ours);

  auto pc = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  to_pcl(input, *pc);
  pcl::IntegralImageNormalEstimation<pcl::PointXYZ, pcl::Normal> ne;
  ne.setNormalEstimationMethod(ne.COVARIANCE_MATRIX);
  ne.setMaxDepthChangeFactor(cfg.max_depth_change_factor);
  ne.setNormalSmoothingSize(cfg.normal_smoothing_size);
  ne.setInputCloud(pc);
  pcl::PointCloud<pcl::Normal> ref;
  ne.compute(ref);

  Comparison c;
  std::vector<double> angles, curv;
  for (std::size_t i = 0; i < input.size(); ++i) {
    const bool a = std::isfinite(ours.nx[i]);
    const bool b = std::isfinite(ref[i].normal_x);
    if (a && b) {
      ++c.both;
      const double dot = double(ours.nx[i]) * ref[i].normal_x + double(ours.ny[i]) * ref[i].normal_y +
                         double(ours.nz[i]) * ref[i].normal_z;
      angles.push_back(std::acos(std::clamp(dot, -1.0, 1.0)) * 180.0 / M_PI);
      curv.push_back(std::abs(double(ours.curvature[i]) - ref[i].curvature));
    } else if (a) {
      ++c.only_ours;
    } else if (b) {
      ++c.only_pcl;
    } else {
      ++c.neither;
    }
  }
  if (!angles.empty()) {
    std::sort(angles.begin(), angles.end());
    std::sort(curv.begin(), curv.end());
    c.median_deg = angles[angles.size() / 2];
    c.p95_deg = angles[angles.size() * 95 / 100];
    c.median_curv_abs = curv[curv.size() / 2];
  }
  return c;
}

}  // namespace

TEST(IntegralNormals, MatchesPclOnSyntheticScene) {
  const auto scene = cropsight::testing::make_synthetic_scene();
  const Comparison c = compare_with_pcl(scene.cloud, {});
  const double total = double(scene.cloud.size());
  const double agreement = double(c.both + c.neither) / total;
  std::cout << "[normals vs PCL] valid in both " << c.both << ", only ours " << c.only_ours << ", only PCL "
            << c.only_pcl << "; validity agreement " << agreement * 100 << " %; median angle " << c.median_deg
            << " deg, p95 " << c.p95_deg << " deg; median |curvature diff| " << c.median_curv_abs << "\n";
  ASSERT_GT(c.both, scene.cloud.size() / 2);
  EXPECT_LT(c.median_deg, 1.0);
  EXPECT_GT(agreement, 0.999);
  EXPECT_LT(c.median_curv_abs, 1e-3);
}

TEST(IntegralNormals, MatchesPclWithOtherParameters) {
  const auto scene = cropsight::testing::make_synthetic_scene({.width = 256, .height = 212});
  const Comparison c = compare_with_pcl(scene.cloud, {.max_depth_change_factor = 0.01f, .normal_smoothing_size = 6.0f});
  std::cout << "[normals vs PCL, factor 0.01 size 6] median angle " << c.median_deg << " deg, only ours " << c.only_ours
            << ", only PCL " << c.only_pcl << "\n";
  ASSERT_GT(c.both, 1000u);
  EXPECT_LT(c.median_deg, 1.0);
  EXPECT_LE(c.only_ours + c.only_pcl, c.both / 1000 + 5);
}

TEST(IntegralNormals, PlaneGivesExactNormalFacingCamera) {
  // Noise-free tilted plane z = 0.8 + 0.2 x: normal ∝ (0.2, 0, -1) facing the camera, curvature 0.
  auto cam = CameraIntrinsics::from_fov(64, 48, 1.2, 1.0);
  OrganizedCloud c(64, 48);
  for (int v = 0; v < 48; ++v)
    for (int u = 0; u < 64; ++u) {
      const double rx = (u - cam.cx) / cam.fx, ry = (v - cam.cy) / cam.fy;
      const double z = 0.8 / (1.0 - 0.2 * rx);
      const int i = c.index(u, v);
      c.x[i] = float(rx * z), c.y[i] = float(ry * z), c.z[i] = float(z);
    }
  geometry::estimate_normals_integral(c);
  const Eigen::Vector3f expect = Eigen::Vector3f(0.2f, 0.0f, -1.0f).normalized();
  int checked = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    if (!std::isfinite(c.nx[i])) continue;
    ++checked;
    EXPECT_GT(c.normal(i).dot(expect), 0.99999f);
    EXPECT_LT(c.curvature[i], 1e-5f);
  }
  EXPECT_EQ(checked, (64 - 20) * (48 - 20));  // everything but the 10-pixel border
}

namespace {
// The tilted plane of the test above, 64x48, with a depth step of `step` m from column 32 on.
OrganizedCloud tilted_plane(float step) {
  auto cam = CameraIntrinsics::from_fov(64, 48, 1.2, 1.0);
  OrganizedCloud c(64, 48);
  for (int v = 0; v < 48; ++v)
    for (int u = 0; u < 64; ++u) {
      const double rx = (u - cam.cx) / cam.fx, ry = (v - cam.cy) / cam.fy;
      const double z = 0.8 / (1.0 - 0.2 * rx) + (u >= 32 ? step : 0.0f);
      const int i = c.index(u, v);
      c.x[i] = float(rx * z), c.y[i] = float(ry * z), c.z[i] = float(z);
    }
  return c;
}
}  // namespace

// nan_breaks_window = false (ours, for ToF dropouts): holes no longer keep the windows around
// them from a normal, while a real depth step still does and a window with too few valid pixels
// gives none. PCL's rule (the default) loses every pixel within about two pixels of a hole.
TEST(IntegralNormals, HolesNeedNotBreakTheWindow) {
  OrganizedCloud c = tilted_plane(0.0f);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  auto punch = [&](int u, int v) { c.x[c.index(u, v)] = c.y[c.index(u, v)] = c.z[c.index(u, v)] = nan; };
  for (int v = 0; v < 48; v += 5)
    for (int u = (v * 3) % 7; u < 64; u += 7) punch(u, v);  // scattered dropouts
  for (int v = 20; v < 24; ++v)
    for (int u = 30; u < 34; ++u) punch(u, v);  // and a 4x4 hole
  const Eigen::Vector3f expect = Eigen::Vector3f(0.2f, 0.0f, -1.0f).normalized();
  auto count = [&](const OrganizedCloud& k) {
    int n = 0, finite_inner = 0;
    for (int v = 10; v < 38; ++v)
      for (int u = 10; u < 54; ++u) {
        const auto i = std::size_t(k.index(u, v));
        if (!std::isfinite(k.z[i])) continue;
        ++finite_inner;
        if (!std::isfinite(k.nx[i])) continue;
        ++n;
        EXPECT_GT(k.normal(i).dot(expect), 0.99999f) << u << "," << v;
      }
    return std::pair{n, finite_inner};
  };
  OrganizedCloud pcl_rule = c;
  geometry::estimate_normals_integral(pcl_rule);
  const auto [with_pcl_rule, inner] = count(pcl_rule);
  EXPECT_LT(with_pcl_rule, inner / 2);  // the holes are everywhere within reach
  OrganizedCloud ours = c;
  geometry::estimate_normals_integral(ours, {.nan_breaks_window = false});
  EXPECT_EQ(count(ours).first, inner);  // every valid pixel inside the border

  // A 5 cm step (limit at 0.8 m: 0.02 * 1.8 * 2 = 7.2 cm; so factor 0.01: 3.6 cm) still breaks windows.
  OrganizedCloud step = tilted_plane(0.05f);
  geometry::estimate_normals_integral(step, {.max_depth_change_factor = 0.01f, .nan_breaks_window = false});
  int near_step = 0;
  for (int v = 10; v < 38; ++v)
    for (int u = 28; u < 36; ++u)
      if (std::isfinite(step.nx[std::size_t(step.index(u, v))])) {
        ++near_step;
        // (beyond the step the surface is z + 5 cm, not quite the plane: 0.9999; a window across
        // the step would tilt the normal by degrees)
        EXPECT_GT(step.normal(std::size_t(step.index(u, v))).dot(expect), 0.9999f) << u << "," << v;
      }
  EXPECT_LT(near_step, 8 * 28);

  // Three pixels of four missing: below min_valid_fraction 0.5 no normal, at 0.2 the plane's.
  OrganizedCloud sparse = tilted_plane(0.0f);
  for (int v = 0; v < 48; ++v)
    for (int u = 0; u < 64; ++u)
      if (u % 2 != 0 || v % 2 != 0)
        sparse.x[sparse.index(u, v)] = sparse.y[sparse.index(u, v)] = sparse.z[sparse.index(u, v)] = nan;
  OrganizedCloud half = sparse, fifth = sparse;
  geometry::estimate_normals_integral(half, {.nan_breaks_window = false});
  geometry::estimate_normals_integral(fifth, {.nan_breaks_window = false, .min_valid_fraction = 0.2f});
  int n_half = 0, n_fifth = 0;
  for (std::size_t i = 0; i < sparse.size(); ++i) {
    n_half += std::isfinite(half.nx[i]);
    if (std::isfinite(fifth.nx[i])) {
      ++n_fifth;
      EXPECT_GT(fifth.normal(i).dot(expect), 0.99999f);
    }
  }
  EXPECT_EQ(n_half, 0);
  EXPECT_EQ(n_fifth, 22 * 14);  // the valid pixels (even u, v) inside the 10-pixel border
}

TEST(IntegralNormals, RejectsBadConfig) {
  OrganizedCloud c(32, 32);
  EXPECT_THROW(
      geometry::estimate_normals_integral(c, {.max_depth_change_factor = 0.02f, .normal_smoothing_size = 0.0f}), Error);
  EXPECT_THROW(geometry::estimate_normals_integral(c, {.max_depth_change_factor = -1.0f}), Error);
  EXPECT_THROW(geometry::estimate_normals_integral(c, {.min_valid_fraction = 1.5f}), Error);
}

TEST(IntegralNormals, TinyCloudIsAllNaN) {
  OrganizedCloud c(8, 8);
  for (std::size_t i = 0; i < c.size(); ++i) c.x[i] = 0, c.y[i] = 0, c.z[i] = 1;
  geometry::estimate_normals_integral(c);
  ASSERT_TRUE(c.has_normals());
  for (std::size_t i = 0; i < c.size(); ++i) EXPECT_TRUE(std::isnan(c.nx[i]));
}

TEST(IntegralNormals, SelectionGivesTheSameValuesOnSelectedPixelsOnly) {
  // The lazy path OES uses: normals only where select[i] >= 0, bit-identical to the full run.
  const auto scene = cropsight::testing::make_synthetic_scene();
  OrganizedCloud full = scene.cloud, part = scene.cloud;
  geometry::IntegralNormalEstimator est;
  est.compute(full);
  std::vector<int> select(part.size(), -1);
  std::size_t chosen = 0;
  for (std::size_t i = 0; i < select.size(); ++i)
    if (scene.cloud.labels[i] != 0 || (i / 7) % 3 == 0) select[i] = 0, ++chosen;
  est.compute(part, select);
  std::size_t finite = 0;
  for (std::size_t i = 0; i < part.size(); ++i) {
    if (select[i] < 0) {
      EXPECT_TRUE(std::isnan(part.nx[i]) && std::isnan(part.curvature[i])) << i;
      continue;
    }
    ASSERT_EQ(std::isfinite(part.nx[i]), std::isfinite(full.nx[i])) << i;
    if (!std::isfinite(full.nx[i])) continue;
    ++finite;
    EXPECT_EQ(part.nx[i], full.nx[i]);
    EXPECT_EQ(part.ny[i], full.ny[i]);
    EXPECT_EQ(part.nz[i], full.nz[i]);
    EXPECT_EQ(part.curvature[i], full.curvature[i]);
  }
  EXPECT_GT(finite, chosen / 3);
  EXPECT_THROW(est.compute(part, std::vector<int>(3, 0)), Error);
}
