// FeatureSet parsing, names and dimensions; viewpoint-angle histogram, geometric features and
// CVFH (through PCL) on simple shapes.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "cropsight/core/error.hpp"
#include "cropsight/features/feature_set.hpp"
#include "cropsight/features/viewpoint_angle.hpp"
#include "cropsight/geometry/integral_normals.hpp"
#include "geometry/synthetic_scene.hpp"

using namespace cropsight;
using features::FeatureSet;

TEST(FeatureSet, ParseSpecNamesAndDimension) {
  const auto fs = FeatureSet::parse("vfh, va,geom");
  EXPECT_EQ(fs.spec(), "vfh,va,geom");
  EXPECT_EQ(fs.dimension(), 308u + 12u + 5u);
  const auto names = fs.names();
  ASSERT_EQ(names.size(), fs.dimension());
  EXPECT_EQ(names[0], "vfh_0");
  EXPECT_EQ(names[307], "vfh_307");
  EXPECT_EQ(names[308], "va_0");
  EXPECT_EQ(names[320], "geom_area");
  EXPECT_EQ(names[324], "geom_symmetry");
  EXPECT_EQ(FeatureSet::parse("cvfh").dimension(), 308u);
  EXPECT_THROW(FeatureSet::parse(""), Error);
  EXPECT_THROW(FeatureSet::parse("vfh,vfh"), Error);
  EXPECT_THROW(FeatureSet::parse("vfh,shot"), Error);
  try {
    FeatureSet::parse("bogus", "model.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.where(), "model.json");
  }
}

namespace {
// A w×h patch of the sphere of radius R centred at (0, 0, zc): a dome facing the camera, or
// (sign -1) a bowl. Normals are exact (towards the camera).
OrganizedCloud sphere_patch(int w, int h, double r, double zc, double sign, double pitch) {
  OrganizedCloud c(w, h);
  c.allocate_normals();
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const double x = (u - (w - 1) / 2.0) * pitch, y = (v - (h - 1) / 2.0) * pitch;
      const double dz = std::sqrt(std::max(0.0, r * r - x * x - y * y));
      const double z = zc - sign * dz;
      const int i = c.index(u, v);
      c.x[i] = float(x), c.y[i] = float(y), c.z[i] = float(z);
      Eigen::Vector3d n = sign * Eigen::Vector3d(x, y, z - zc) / r;
      if (n.z() > 0) n = -n;
      c.nx[i] = float(n.x()), c.ny[i] = float(n.y()), c.nz[i] = float(n.z());
      c.curvature[i] = 0.0f;
    }
  return c;
}
std::vector<int> disc(const OrganizedCloud& c, double radius_px) {
  std::vector<int> idx;
  for (int v = 0; v < c.height; ++v)
    for (int u = 0; u < c.width; ++u) {
      const double du = u - (c.width - 1) / 2.0, dv = v - (c.height - 1) / 2.0;
      if (du * du + dv * dv <= radius_px * radius_px) idx.push_back(c.index(u, v));
    }
  return idx;
}
}  // namespace

TEST(ViewpointAngle, FrontoParallelPlaneFillsFirstBin) {
  OrganizedCloud c(3, 1);
  c.allocate_normals();
  for (int i = 0; i < 3; ++i) c.x[i] = 0, c.y[i] = 0, c.z[i] = 1, c.nx[i] = 0, c.ny[i] = 0, c.nz[i] = -1;
  // Third point: normal at 80° from the viewing direction → bin floor(80 / 7.5) = 10.
  c.nx[2] = float(std::sin(80 * M_PI / 180)), c.nz[2] = -float(std::cos(80 * M_PI / 180));
  float h[12];
  const std::vector<int> idx = {0, 1, 2};
  features::compute_viewpoint_angle_histogram(c, idx, h);
  EXPECT_NEAR(h[0], 2.0f / 3.0f, 1e-6);
  EXPECT_NEAR(h[10], 1.0f / 3.0f, 1e-6);
  EXPECT_NEAR(std::accumulate(h, h + 12, 0.0f), 1.0f, 1e-6);
}

TEST(GeometricFeatures, DomeVersusBowlVersusPlane) {
  const double pitch = 0.002;
  const auto dome = sphere_patch(81, 81, 0.1, 0.9, 1.0, pitch);
  const auto bowl = sphere_patch(81, 81, 0.1, 0.7, -1.0, pitch);
  const auto plane = sphere_patch(81, 81, 1e6, 0.8 + 1e6, 1.0, pitch);  // huge sphere ≈ plane
  features::GeometricWorkspace ws;
  float gd[5], gb[5], gp[5];
  const auto idx = disc(dome, 30.0);
  features::compute_geometric_features(dome, idx, ws, gd);
  features::compute_geometric_features(bowl, idx, ws, gb);
  features::compute_geometric_features(plane, idx, ws, gp);
  // Area: the flat disc of radius 30 px·2 mm = 0.06 m has area ≈ π·0.06² = 0.0113 m²; the
  // spherical cap over it is larger (2πR·h, h = R - sqrt(R² - a²)).
  const double a = 0.06, cap = 2 * M_PI * 0.1 * (0.1 - std::sqrt(0.01 - a * a));
  EXPECT_NEAR(gp[0], M_PI * a * a, 0.08 * M_PI * a * a);
  EXPECT_NEAR(gd[0], cap, 0.08 * cap);
  // Compactness of a digital disc ≈ 1.
  EXPECT_NEAR(gp[1], 1.0, 0.1);
  // Smoothness: plane ≈ 0, sphere ≈ pitch/R rad per pixel step (larger).
  EXPECT_LT(gp[2], 1e-3);
  EXPECT_GT(gd[2], 0.01);
  // Convexity: dome ≈ 1, bowl ≈ 0.
  EXPECT_GT(gd[3], 0.95);
  EXPECT_LT(gb[3], 0.05);
  // Symmetric disc: symmetry ≈ 1. A triangle (density ∝ t along its axis: skewness -0.57) is
  // lopsided: exp(-0.57/2) ≈ 0.75; it is also less compact than the disc.
  EXPECT_GT(gd[4], 0.95);
  std::vector<int> triangle;
  for (int u = 10; u <= 70; ++u)
    for (int v = 0; v < 81; ++v)
      if (std::abs(v - 40) <= (u - 10) / 2) triangle.push_back(dome.index(u, v));
  float gt[5];
  features::compute_geometric_features(dome, triangle, ws, gt);
  EXPECT_LT(gt[4], 0.85);
  EXPECT_LT(gt[1], gd[1]);
}

TEST(FeatureSet, ComputeConcatenatesInSpecOrder) {
  auto scene = cropsight::testing::make_synthetic_scene({.width = 256, .height = 212});
  geometry::estimate_normals_integral(scene.cloud);
  std::vector<int> idx;
  for (std::size_t i = 0; i < scene.cloud.size(); ++i)
    if (scene.cloud.labels[i] == 1 && std::isfinite(scene.cloud.nx[i])) idx.push_back(int(i));
  ASSERT_GT(idx.size(), 200u);
  const auto fs = FeatureSet::parse("va,vfh,geom,cvfh");
  std::vector<float> f;
  fs.compute(scene.cloud, idx, {}, f);
  ASSERT_EQ(f.size(), fs.dimension());
  float va[12];
  features::compute_viewpoint_angle_histogram(scene.cloud, idx, va);
  for (int b = 0; b < 12; ++b) EXPECT_EQ(f[b], va[b]);
  const auto vfh = features::compute_vfh(scene.cloud, idx);
  for (int b = 0; b < 308; ++b) EXPECT_EQ(f[12 + b], vfh[b]);
  for (float v : f) EXPECT_TRUE(std::isfinite(v));
  // CVFH (PCL) of a dome: a non-empty histogram whose viewpoint part is populated.
  double cvfh_mass = 0;
  for (int b = 0; b < 308; ++b) cvfh_mass += f[12 + 308 + 5 + b];
  EXPECT_GT(cvfh_mass, 0.0);
  OrganizedCloud no_normals(4, 4);
  EXPECT_THROW(fs.compute(no_normals, std::vector<int>{0}, {}, f), Error);
}
