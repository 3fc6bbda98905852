// Box-centre deprojection against hand-computed cases, the robust depth window on noisy and holey
// depth, the centre behind the surface (silhouette rule on a ray-cast ellipsoid), depth_ok at the
// D415's minimum range, and ripeness by metric box area.
#include <gtest/gtest.h>

#include <cmath>

#include "cropsight/core/error.hpp"
#include "cropsight/measure/position.hpp"

using namespace cropsight;
using namespace cropsight::measure;

namespace {

CameraIntrinsics camera() {
  CameraIntrinsics c;
  c.width = 640;
  c.height = 480;
  c.fx = 600;
  c.fy = 500;
  c.cx = 320;
  c.cy = 240;
  return c;
}

Detection2D box(float x1, float y1, float x2, float y2) {
  Detection2D d;
  d.x1 = x1, d.y1 = y1, d.x2 = x2, d.y2 = y2;
  return d;
}

PositionConfig surface_config() {
  PositionConfig cfg;
  cfg.centre_offset = CentreOffset::surface;
  return cfg;
}

}  // namespace

TEST(Position, DeprojectsTheBoxCentreByHand) {
  // Box [400.5, 460.5) x [100.5, 160.5): continuous centre (430.5, 130.5) = pixel centre (430, 130).
  // At z = 0.4 m: x = (430 - 320) / 600 * 0.4 = 0.0733.. m, y = (130 - 240) / 500 * 0.4 = -0.088 m.
  // Width 60 px * 0.4 / 600 = 0.04 m, height 60 px * 0.4 / 500 = 0.048 m.
  Image<float> depth(640, 480, 0.4f);
  const Position3D p = locate(box(400.5f, 100.5f, 460.5f, 160.5f), depth, camera(), surface_config());
  ASSERT_TRUE(p.depth_ok);
  EXPECT_NEAR(p.xyz.x(), 110.0 / 600 * 0.4, 1e-6);
  EXPECT_NEAR(p.xyz.y(), -110.0 / 500 * 0.4, 1e-6);
  EXPECT_NEAR(p.xyz.z(), 0.4, 1e-6);
  EXPECT_NEAR(p.width_m, 0.04, 1e-6);
  EXPECT_NEAR(p.height_m, 0.048, 1e-6);
  EXPECT_NEAR(p.area_m2, 0.04 * 0.048, 1e-8);
}

TEST(Position, HalfWidthOffsetFindsTheCentreOfASphere) {
  // A sphere of radius r = 0.03 m centred at z = 0.43 m on the optical axis: surface depth 0.40 m,
  // silhouette half-angle asin(r / zc); box half-width f * tan(asin(r / zc)).
  const double r = 0.03, zc = 0.43, half = 600 * std::tan(std::asin(r / zc));
  const double halfy = 500 * std::tan(std::asin(r / zc));
  Image<float> depth(640, 480, float(zc - r));
  PositionConfig cfg;
  cfg.centre_offset = CentreOffset::half_width;
  const Position3D p = locate(box(float(320.5 - half), float(240.5 - halfy), float(320.5 + half), float(240.5 + halfy)),
                              depth, camera(), cfg);
  ASSERT_TRUE(p.depth_ok);
  EXPECT_NEAR(p.xyz.z(), zc, 0.001);  // perspective: the silhouette is a little in front of the centre
  EXPECT_NEAR(p.xyz.x(), 0.0, 1e-6);
  EXPECT_NEAR(p.width_m, 2 * r, 0.001);
}

// Ray-cast depth of an ellipsoid (semi-axes a along the image direction `angle`, b across it in the
// image plane, c along the view) centred at `c0`, in front of a backdrop at 0.7 m, with a root
// (a vertical strip 3 cm in front of the potato) crossing it; and the box of its silhouette.
namespace {
struct Rendered {
  Image<float> depth{640, 480, 0.7f};
  Detection2D box;
};
// `tilt` turns the length axis toward the camera (radians); `quantum_m` rounds the depth like the
// D415's 1 mm units (0: exact).
Rendered render_ellipsoid(const Eigen::Vector3d& c0, double a, double b, double c, double angle, double tilt = 0,
                          double quantum_m = 0) {
  Rendered out;
  const CameraIntrinsics cam = camera();
  const Eigen::Vector3d a0(std::cos(angle), -std::sin(angle), 0), bx(std::sin(angle), std::cos(angle), 0);
  const Eigen::Vector3d ax = std::cos(tilt) * a0 - std::sin(tilt) * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d cz = ax.cross(bx).normalized();
  Eigen::Matrix3d A = ax * ax.transpose() / (a * a) + bx * bx.transpose() / (b * b) + cz * cz.transpose() / (c * c);
  float u0 = 1e9f, v0 = 1e9f, u1 = -1, v1 = -1;
  for (int v = 0; v < 480; ++v)
    for (int u = 0; u < 640; ++u) {
      const Eigen::Vector3d d((u - cam.cx) / cam.fx, (v - cam.cy) / cam.fy, 1.0);
      // (t d - c0)^T A (t d - c0) = 1
      const double qa = d.dot(A * d), qb = -2 * d.dot(A * c0), qc = c0.dot(A * c0) - 1;
      const double disc = qb * qb - 4 * qa * qc;
      if (disc < 0) continue;
      const double t = (-qb - std::sqrt(disc)) / (2 * qa);
      out.depth.at(u, v) = float(quantum_m > 0 ? quantum_m * std::round(t / quantum_m) : t);
      u0 = std::min(u0, float(u)), u1 = std::max(u1, float(u + 1)), v0 = std::min(v0, float(v)),
      v1 = std::max(v1, float(v + 1));
    }
  out.box = box(u0, v0, u1, v1);
  const int root_u = int(std::lround(0.5f * (u0 + u1) + 0.2f * (u1 - u0)));
  for (int v = 0; v < 480; ++v)
    for (int u = root_u; u < root_u + 4; ++u) out.depth.at(u, v) = float(c0.z() - c - 0.03);
  return out;
}
}  // namespace

TEST(Position, SilhouetteOffsetFindsTheCentreOfAnEllipsoidAtAnAngle) {
  // A potato 9 x 5.6 x 5.6 cm lying at 45 deg in the image, centre 0.42 m away, 3 cm right of the axis.
  const Eigen::Vector3d c0(0.03, -0.01, 0.42);
  const Rendered r = render_ellipsoid(c0, 0.045, 0.028, 0.028, M_PI / 4);
  PositionConfig rule;
  rule.centre_offset = CentreOffset::silhouette;
  const Position3D p = locate(r.box, r.depth, camera(), rule);
  ASSERT_TRUE(p.depth_ok);
  EXPECT_NEAR(p.xyz.z(), c0.z(), 0.0015);
  EXPECT_NEAR(p.xyz.x(), c0.x(), 0.001);
  EXPECT_NEAR(p.xyz.y(), c0.y(), 0.001);
  EXPECT_NEAR(p.minor_m, 0.056, 0.003);
  EXPECT_NEAR(p.major_m, 0.09, 0.005);
  // The cause of the older rule's far bias: the axis-aligned box of a potato at 45 deg is about
  // (a + b) / sqrt(2) wide, so half its side overshoots the semi-axis by about 1 cm here.
  PositionConfig box_rule;
  box_rule.centre_offset = CentreOffset::half_width;
  EXPECT_GT(locate(r.box, r.depth, camera(), box_rule).xyz.z() - c0.z(), 0.006);
  // Lying along the image x axis, the two rules agree.
  const Rendered flat = render_ellipsoid(c0, 0.045, 0.028, 0.028, 0.0);
  EXPECT_NEAR(locate(flat.box, flat.depth, camera(), rule).xyz.z(), c0.z(), 0.0015);
  EXPECT_NEAR(locate(flat.box, flat.depth, camera(), box_rule).xyz.z(), c0.z(), 0.0015);
  // 24 deg off the optical axis, standing upright: in plain image coordinates the silhouette is
  // stretched sideways (radially) by 1 / cos 24 deg; measured across the ray to it, it is not.
  const Eigen::Vector3d c1(-0.15, 0.06, 0.36);
  const Rendered side = render_ellipsoid(c1, 0.04, 0.033, 0.033, M_PI / 2);
  const Position3D q = locate(side.box, side.depth, camera(), rule);
  ASSERT_TRUE(q.depth_ok);
  EXPECT_NEAR((q.xyz.cast<double>() - c1).norm(), 0.0, 0.002);
  EXPECT_NEAR(q.minor_m, 0.066, 0.003);
}

TEST(Position, ProfileOffsetMeasuresTheThicknessTheSilhouetteCannotShow) {
  // Potatoes 9 x 6 cm across the view, 4.4 or 7.2 cm thick along it, at 45 deg, 1 mm depth units,
  // a root in front. The silhouette rule takes the thickness to be the width (6 cm): 8 mm too far
  // for the flat one and 6 mm too near for the thick one. The profile fit sees the curvature.
  const Eigen::Vector3d c0(0.03, -0.01, 0.42);
  PositionConfig silhouette_rule;
  silhouette_rule.centre_offset = CentreOffset::silhouette;
  PositionConfig profile;
  profile.centre_offset = CentreOffset::profile;
  for (const double thickness : {0.044, 0.072}) {
    const Rendered r = render_ellipsoid(c0, 0.045, 0.03, 0.5 * thickness, M_PI / 4, 0.0, 0.001);
    const Position3D s = locate(r.box, r.depth, camera(), silhouette_rule);
    EXPECT_GT(std::abs(s.xyz.z() - c0.z()), 0.005) << thickness;
    const Position3D p = locate(r.box, r.depth, camera(), profile);
    ASSERT_TRUE(p.depth_ok);
    EXPECT_NEAR(p.thickness_m, thickness, 0.003) << thickness;
    EXPECT_NEAR((p.xyz.cast<double>() - c0).norm(), 0.0, 0.0015) << thickness;
  }
  // Tilted 20 deg toward the camera and 24 deg off the optical axis: the rim's plane is tilted,
  // which the fit's linear terms take up.
  const Eigen::Vector3d c1(-0.15, 0.06, 0.36);
  const Rendered t = render_ellipsoid(c1, 0.045, 0.03, 0.025, 1.0, 0.35, 0.001);
  const Position3D p = locate(t.box, t.depth, camera(), profile);
  ASSERT_TRUE(p.depth_ok);
  EXPECT_GT(p.thickness_m, 0.f);
  EXPECT_NEAR((p.xyz.cast<double>() - c1).norm(), 0.0, 0.002);
  // A thickness outside profile_max_ratio of the width (a flat patch: a box on the backdrop) falls
  // back to the silhouette rule.
  Image<float> wall(640, 480, 0.5f);
  const Position3D flat = locate(box(300, 200, 360, 260), wall, camera(), profile);
  EXPECT_EQ(flat.thickness_m, 0.f);
  EXPECT_NEAR(flat.xyz.z(), locate(box(300, 200, 360, 260), wall, camera(), silhouette_rule).xyz.z(), 1e-6);
}

TEST(Position, GrownSilhouetteRecoversAnEndTheBoxCutsOff) {
  // The detector's box misses the right 8 % of the potato (a dark end): the silhouette inside the
  // box is narrower and off-centre; grown by depth connectivity beyond the box, it is whole again.
  const Eigen::Vector3d c0(0.02, 0.0, 0.4);
  const Rendered r = render_ellipsoid(c0, 0.045, 0.03, 0.03, 0.0, 0.0, 0.001);
  Detection2D cut = r.box;
  cut.x2 -= 0.08f * r.box.width();
  PositionConfig boxed;
  boxed.silhouette_grow = 0;
  PositionConfig grown;
  grown.silhouette_grow = 0.1;
  grown.silhouette_opening_px = 0;  // pixel counts comparable with the box's (the opening trims the rim)
  for (const CentreOffset offset : {CentreOffset::silhouette, CentreOffset::profile}) {
    boxed.centre_offset = grown.centre_offset = offset;
    const Position3D whole = locate(r.box, r.depth, camera(), boxed);
    const Position3D inside = locate(cut, r.depth, camera(), boxed);
    const Position3D regrown = locate(cut, r.depth, camera(), grown);
    EXPECT_LT(inside.silhouette_pixels, whole.silhouette_pixels);
    EXPECT_EQ(regrown.silhouette_pixels, whole.silhouette_pixels);
    EXPECT_GT((inside.xyz.cast<double>() - c0).norm(), 0.002);
    EXPECT_NEAR((regrown.xyz.cast<double>() - c0).norm(), 0.0, 0.0015);
  }
  // The root 3 cm in front and the backdrop are not connected to the potato: growing the whole
  // box's silhouette adds nothing.
  EXPECT_EQ(locate(r.box, r.depth, camera(), grown).silhouette_pixels,
            locate(r.box, r.depth, camera(), boxed).silhouette_pixels);
}

TEST(Position, MedianWindowIgnoresHolesAndARootInFront) {
  Image<float> depth(640, 480, 0.5f);
  const Detection2D b = box(300, 200, 360, 260);  // 60 x 60 px: window 18 x 18
  // Holes over a third of the window, and a root (0.45 m) over another 20 %.
  for (int v = 200; v < 260; ++v)
    for (int u = 300; u < 360; ++u) {
      if ((u + v) % 3 == 0) depth.at(u, v) = 0;
      if (u >= 328 && u < 332) depth.at(u, v) = 0.45f;
    }
  depth.at(330, 230) = 0.0f;  // the centre pixel itself is a hole
  const Position3D robust = locate(b, depth, camera(), surface_config());
  EXPECT_TRUE(robust.depth_ok);
  EXPECT_FLOAT_EQ(robust.surface_depth_m, 0.5f);
  EXPECT_EQ(robust.window_pixels, 18 * 18);
  EXPECT_LT(robust.valid_pixels, robust.window_pixels);

  PositionConfig paper = surface_config();
  paper.sampling = DepthSampling::centre_pixel;
  const Position3D centre = locate(b, depth, camera(), paper);
  EXPECT_FALSE(centre.depth_ok);  // the paper's one pixel is a hole
  depth.at(330, 230) = 0.45f;
  EXPECT_FLOAT_EQ(locate(b, depth, camera(), paper).surface_depth_m, 0.45f);  // ... or the root
}

TEST(Position, MedianOfNoisyDepthIsCloseToTheTruth) {
  Image<float> depth(640, 480, 0.f);
  std::uint32_t s = 12345;
  for (auto& d : depth.data) {
    s = s * 1664525u + 1013904223u;
    d = 0.4f + 0.004f * (float(s >> 8) / float(1u << 24) - 0.5f);  // +-2 mm uniform
  }
  const Position3D p = locate(box(280, 200, 360, 280), depth, camera(), surface_config());
  EXPECT_NEAR(p.surface_depth_m, 0.4, 0.0005);
}

TEST(Position, DepthOkFalseBelowMinimumRangeOrTooFewPixels) {
  Image<float> depth(640, 480, 0.2f);
  EXPECT_FALSE(locate(box(300, 200, 340, 240), depth, camera()).depth_ok);  // 0.2 m < 0.25 m
  Image<float> holes(640, 480, 0.f);
  holes.at(320, 220) = 0.4f;  // one valid pixel of 144
  const Position3D p = locate(box(300, 200, 340, 240), holes, camera());
  EXPECT_FALSE(p.depth_ok);
  EXPECT_EQ(p.valid_pixels, 1);
  EXPECT_FALSE(locate(box(300, 200, 340, 240), Image<float>{}, camera()).depth_ok);
  EXPECT_FALSE(locate(box(700, 200, 740, 240), depth, camera()).depth_ok);  // outside the image
}

TEST(Position, RipenessByAreaAtDepth) {
  Image<float> depth(640, 480, 0.4f);
  const Position3D p = locate(box(300, 200, 360, 260), depth, camera(), surface_config());  // 0.04 x 0.048 m
  RipenessConfig cfg;
  EXPECT_TRUE(is_ripe(p, cfg));  // paper: threshold 0, every potato with depth is ripe
  cfg.ripeness_threshold_m2 = 0.0019;
  EXPECT_TRUE(is_ripe(p, cfg));
  cfg.ripeness_threshold_m2 = 0.0020;
  EXPECT_FALSE(is_ripe(p, cfg));
  Position3D no_depth = p;
  no_depth.depth_ok = false;
  EXPECT_FALSE(is_ripe(no_depth, RipenessConfig{}));
}

TEST(Position, ConfigRulesAndMetres) {
  PositionConfig cfg;
  cfg.max_depth_m = 0.1;
  EXPECT_THROW(cfg.validate("test"), Error);
  DepthImage raw(2, 1, 0);
  raw.at(0, 0) = 400;
  const Image<float> m = depth_in_metres(raw, 0.001);
  EXPECT_FLOAT_EQ(m.at(0, 0), 0.4f);
  EXPECT_FLOAT_EQ(m.at(1, 0), 0.f);
}
