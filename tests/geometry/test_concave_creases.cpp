// Concave creases (concave_creases.hpp) on ray-cast surfaces with the integral-image normals: a
// valley is marked along its fold and nowhere else; a ridge and a dome (a head) are not marked.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <vector>

#include "cropsight/core/camera.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/geometry/concave_creases.hpp"
#include "cropsight/geometry/integral_normals.hpp"

using namespace cropsight;

namespace {
constexpr int kW = 160, kH = 120;

// Ray-casts depth(rx, ry) (the depth along the ray with slopes rx, ry) and computes the normals.
OrganizedCloud cast(const std::function<float(float, float)>& depth) {
  const auto cam = CameraIntrinsics::from_fov(kW, kH, 70.6 * M_PI / 180.0, 60.0 * M_PI / 180.0);
  OrganizedCloud c(kW, kH);
  for (int v = 0; v < kH; ++v)
    for (int u = 0; u < kW; ++u) {
      const float rx = float((u - cam.cx) / cam.fx), ry = float((v - cam.cy) / cam.fy);
      const float z = depth(rx, ry);
      const std::size_t i = std::size_t(v) * kW + u;
      c.x[i] = rx * z, c.y[i] = ry * z, c.z[i] = z;
    }
  // A small smoothing window keeps the fold sharp: with the detector's 10 px the normals turn over
  // about 20 px and pairs 3 px apart differ by less than 10°.
  geometry::IntegralNormalConfig cfg;
  cfg.normal_smoothing_size = 4.0f;
  geometry::IntegralNormalEstimator(cfg).compute(c);
  return c;
}
std::vector<std::uint8_t> marks_of(const OrganizedCloud& c, const geometry::ConcaveCreaseOptions& o = {}) {
  std::vector<int> all(c.size());
  std::iota(all.begin(), all.end(), 0);
  std::vector<std::uint8_t> marks(c.size(), 0);
  geometry::mark_concave_creases(c, all, o, marks);
  return marks;
}
// Marked pixels, and how many of them lie more than `band` pixels from column `fold`.
std::pair<int, int> count(const std::vector<std::uint8_t>& marks, int fold, int band) {
  int all = 0, away = 0;
  for (std::size_t i = 0; i < marks.size(); ++i)
    if (marks[i]) ++all, away += std::abs(int(i % kW) - fold) > band;
  return {all, away};
}
}  // namespace

TEST(ConcaveCreases, MarksTheFoldOfAValleyOnly) {
  // Valley along the image's y axis: the fold (x = 0) is farthest from the camera, each side rises
  // towards it with slope 0.5 (normals 53° apart): z = 0.8 - 0.5 |x|, i.e. z = 0.8 / (1 + 0.5 |rx|).
  const OrganizedCloud valley = cast([](float rx, float) { return 0.8f / (1.0f + 0.5f * std::abs(rx)); });
  const auto marks = marks_of(valley);
  const auto [all, away] = count(marks, kW / 2, 12);
  EXPECT_EQ(away, 0) << "planes away from the fold are not creases";
  int rows = 0;
  for (int v = 0; v < kH; ++v)
    rows += std::any_of(marks.begin() + v * kW, marks.begin() + (v + 1) * kW, [](std::uint8_t m) { return m != 0; });
  EXPECT_GE(rows, kH - 12) << "the fold is marked on every row with normals (none within the window of the border)";
  EXPECT_GE(all, 2 * rows);
}

TEST(ConcaveCreases, LeavesRidgesDomesAndPlanesUnmarked) {
  // The same fold turned towards the camera (convex): z = 0.8 + 0.5 |x|.
  const OrganizedCloud ridge = cast([](float rx, float) { return 0.8f / (1.0f - 0.5f * std::abs(rx)); });
  EXPECT_EQ(count(marks_of(ridge), kW / 2, 0).first, 0);
  // A paraboloid dome, its top nearest the camera: z = 0.8 + 3 (x² + y²) (a head's curvature).
  const OrganizedCloud dome = cast([](float rx, float ry) {
    const float r2 = rx * rx + ry * ry, a = 3.0f, z0 = 0.8f;
    return r2 == 0.0f ? z0 : (1.0f - std::sqrt(1.0f - 4.0f * a * r2 * z0)) / (2.0f * a * r2);
  });
  EXPECT_EQ(count(marks_of(dome), kW / 2, 0).first, 0);
  const OrganizedCloud plane = cast([](float rx, float ry) { return 0.8f / (1.0f - 0.2f * rx - 0.1f * ry); });
  EXPECT_EQ(count(marks_of(plane), kW / 2, 0).first, 0);
}

TEST(ConcaveCreases, AnAngleAboveTheFoldsMarksNothing) {
  const OrganizedCloud valley = cast([](float rx, float) { return 0.8f / (1.0f + 0.5f * std::abs(rx)); });
  EXPECT_EQ(count(marks_of(valley, {60.0f, 3}), kW / 2, 0).first, 0) << "the sides are 53° apart";
  const int at20 = count(marks_of(valley, {20.0f, 3}), kW / 2, 0).first;
  EXPECT_GT(at20, count(marks_of(valley, {40.0f, 3}), kW / 2, 0).first);
  EXPECT_GT(count(marks_of(valley, {20.0f, 6}), kW / 2, 0).first, at20) << "a longer step sees more of the fold";
}

TEST(ConcaveCreases, RejectsBadInput) {
  const OrganizedCloud valley = cast([](float rx, float) { return 0.8f / (1.0f + 0.5f * std::abs(rx)); });
  std::vector<std::uint8_t> marks(valley.size(), 0), short_marks(10, 0);
  const std::vector<int> ok = {0, 1}, outside = {int(valley.size())};
  EXPECT_THROW(geometry::mark_concave_creases(valley, ok, {0.0f, 3}, marks), Error);
  EXPECT_THROW(geometry::mark_concave_creases(valley, ok, {30.0f, 0}, marks), Error);
  EXPECT_THROW(geometry::mark_concave_creases(valley, ok, {}, short_marks), Error);
  EXPECT_THROW(geometry::mark_concave_creases(valley, outside, {}, marks), Error);
  OrganizedCloud no_normals(4, 4);
  std::vector<std::uint8_t> m16(16, 0);
  no_normals.nx.clear();
  EXPECT_THROW(geometry::mark_concave_creases(no_normals, ok, {}, m16), Error);
}
