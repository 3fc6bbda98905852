// Colour registered to depth (color_registration.hpp), checked against OpenCV's own projection of
// depth into an external camera (cv::rgbd::registerDepth, libopencv-contrib-dev) where present.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>

#include "cropsight/core/error.hpp"
#include "cropsight/io/color_registration.hpp"
#include "testing/testing.hpp"
#if CROPSIGHT_HAS_OPENCV_RGBD
#include <opencv2/core/eigen.hpp>
#include <opencv2/rgbd.hpp>
#endif

namespace cropsight::io {
namespace {

using cropsight::testing::error_message;
using cropsight::testing::TempDir;
using cropsight::testing::write_text;

CameraIntrinsics registration_camera(int w, int h, double f) {
  CameraIntrinsics c;
  c.width = w;
  c.height = h;
  c.fx = f;
  c.fy = f * 1.01;
  c.cx = (w - 1) / 2.0 + 3.0;
  c.cy = (h - 1) / 2.0 - 2.0;
  c.depth_scale = 0.001;
  return c;
}

// A tilted floor 1.1-1.4 m away with a box 0.3 m nearer in front of part of it (an occluder).
DepthImage registration_scene(const CameraIntrinsics& c) {
  DepthImage d(c.width, c.height);
  for (int v = 0; v < c.height; ++v)
    for (int u = 0; u < c.width; ++u) {
      const bool box = u > c.width / 3 && u < c.width / 2 && v > c.height / 3 && v < 2 * c.height / 3;
      d.at(u, v) = (u + 2 * v) % 37 == 0 ? 0 : std::uint16_t((box ? 900 : 1100) + u / 2 + v);
    }
  return d;
}

DepthToColor kinect_like_extrinsics() {
  DepthToColor e;
  e.rotation = Eigen::AngleAxisd(0.02, Eigen::Vector3d(0.3, 1, 0.1).normalized()).toRotationMatrix();
  e.translation = {-0.052, 0.003, 0.001};  // a Kinect v2's colour camera sits ~5 cm beside the depth camera
  return e;
}

// Colour whose pixels say where they are, so the registered image tells which pixel each depth
// pixel took.
ColorImage coordinate_image(int w, int h) {
  ColorImage c(w, h);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u)
      c.at(u, v) = Rgb8{std::uint8_t(u & 255), std::uint8_t(v & 255), std::uint8_t(1 + (u >> 8) + ((v >> 8) << 4))};
  return c;
}

TEST(ColorRegistration, SameCameraIsTheIdentityWhereDepthIsValid) {
  const CameraIntrinsics c = registration_camera(64, 48, 60);
  const DepthImage d = registration_scene(c);
  const ColorImage color = coordinate_image(c.width, c.height);
  const ColorImage r = register_color(d, c, color, c, DepthToColor{});
  for (std::size_t i = 0; i < d.data.size(); ++i) EXPECT_EQ(r.data[i], d.data[i] ? color.data[i] : Rgb8{});
}

// The floor behind the box, seen by the depth camera but hidden from the colour camera beside
// it, gets no colour (black), never the box's.
TEST(ColorRegistration, OccludedPixelsStayBlack) {
  const CameraIntrinsics c = registration_camera(160, 120, 150);
  const DepthImage d = registration_scene(c);
  DepthToColor e;
  e.translation = {-0.1, 0, 0};
  const ColorImage r = register_color(d, c, ColorImage(c.width, c.height, Rgb8{200, 100, 50}), c, e);
  int black_floor = 0, black_box = 0;
  for (int v = c.height / 3 + 1; v < 2 * c.height / 3; ++v)
    for (int u = 0; u < c.width; ++u) {
      if (d.at(u, v) == 0) continue;
      const bool box = d.at(u, v) < 1000, black = r.at(u, v) == Rgb8{};
      black_floor += !box && black;
      black_box += box && black;
    }
  // The box's shadow on the floor: the colour camera 0.1 m to the left of the depth camera sees
  // ~0.1 m x 0.3 / 1.2 = 2.5 cm less of the floor beside it, some 3 pixels a row here, on 39 rows.
  EXPECT_GT(black_floor, 60);
  EXPECT_EQ(black_box, 0);
}

TEST(ColorRegistration, ExtrinsicsYaml) {
  TempDir t;
  write_text(t / "e.yaml",
             "color_to_depth:\n  rotation: [1, 0, 0, 0, 1, 0, 0, 0, 1]\n  translation: [0.05, -0.01, 0]\n");
  const DepthToColor e = read_extrinsics_yaml(t / "e.yaml");
  EXPECT_NEAR(e.translation.x(), -0.05, 1e-15);  // inverted: depth to colour
  EXPECT_NEAR(e.translation.y(), 0.01, 1e-15);
  write_text(t / "bad.yaml", "depth_to_color:\n  rotation: [1, 0, 0, 0, 2, 0, 0, 0, 1]\n  translation: [0, 0, 0]\n");
  const std::string bad = error_message([&] { read_extrinsics_yaml(t / "bad.yaml"); });
  EXPECT_NE(bad.find("bad.yaml"), std::string::npos);
  EXPECT_NE(bad.find("not a rotation matrix"), std::string::npos);
  write_text(t / "short.yaml", "depth_to_color:\n  rotation: [1, 0, 0]\n  translation: [0, 0, 0]\n");
  EXPECT_NE(error_message([&] { read_extrinsics_yaml(t / "short.yaml"); }).find("list of 9 numbers"),
            std::string::npos);
  write_text(t / "none.yaml", "R: [1]\n");
  EXPECT_NE(error_message([&] { read_extrinsics_yaml(t / "none.yaml"); }).find("'depth_to_color' or 'color_to_depth'"),
            std::string::npos);
}

#if CROPSIGHT_HAS_OPENCV_RGBD
// Each depth pixel's colour pixel (decoded from the coordinate image) must be where OpenCV puts
// that point too: OpenCV's registered depth there is the point's depth in the colour camera.
// The colour camera is finer than depth, with distortion, so OpenCV's image has holes wherever
// no depth pixel landed: a projection one pixel off finds a hole or another depth.
TEST(ColorRegistration, AgreesWithOpenCvRegisterDepth) {
  const CameraIntrinsics dc = registration_camera(160, 120, 150);
  CameraIntrinsics cc = registration_camera(400, 300, 330);
  cc.distortion = {0.08, -0.15, 0.001, -0.0005, 0.05};
  const DepthToColor e = kinect_like_extrinsics();
  const DepthImage d = registration_scene(dc);
  const ColorImage r = register_color(d, dc, coordinate_image(cc.width, cc.height), cc, e);

  cv::Matx33f kd(float(dc.fx), 0, float(dc.cx), 0, float(dc.fy), float(dc.cy), 0, 0, 1);
  cv::Matx33f kc(float(cc.fx), 0, float(cc.cx), 0, float(cc.fy), float(cc.cy), 0, 0, 1);
  cv::Mat rt = cv::Mat::eye(4, 4, CV_32F);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) rt.at<float>(i, j) = float(e.rotation(i, j));
    rt.at<float>(i, 3) = float(e.translation(i));
  }
  cv::Mat depth(d.height, d.width, CV_16UC1, const_cast<std::uint16_t*>(d.data.data()));
  cv::Mat registered;
  cv::rgbd::registerDepth(kd, kc, cv::Mat(cc.distortion), rt, depth, cv::Size(cc.width, cc.height), registered);

  int coloured = 0, agree = 0;
  for (int v = 0; v < d.height; ++v)
    for (int u = 0; u < d.width; ++u) {
      const Rgb8 px = r.at(u, v);
      if (px == Rgb8{}) continue;
      ++coloured;
      const int cu = px.r + ((px.b - 1) & 15) * 256, cv_ = px.g + ((px.b - 1) >> 4) * 256;
      const double z = d.at(u, v) * 0.001;
      const Eigen::Vector3d p((u - dc.cx) / dc.fx * z, (v - dc.cy) / dc.fy * z, z);
      const double zc_mm = (e.rotation * p + e.translation).z() * 1000.0;
      agree += std::abs(double(registered.at<std::uint16_t>(cv_, cu)) - zc_mm) <= 2.0;
    }
  std::printf("registration: %d of %d coloured depth pixels agree with cv::rgbd::registerDepth\n", agree, coloured);
  EXPECT_GT(coloured, d.width * d.height * 8 / 10);
  EXPECT_GE(agree, coloured * 98 / 100) << agree << " of " << coloured << " agree with OpenCV";
}
#endif

}  // namespace
}  // namespace cropsight::io
