#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cropsight/core/camera.hpp"
#include "cropsight/core/error.hpp"

using cropsight::CameraIntrinsics;

TEST(Camera, DeprojectProjectRoundTrip) {
  CameraIntrinsics c =
      CameraIntrinsics::from_fov(512, 424, 70.6 * std::numbers::pi / 180, 60.0 * std::numbers::pi / 180);
  const Eigen::Vector3f p = c.deproject(100.0f, 300.0f, 1.25f);
  EXPECT_FLOAT_EQ(p.z(), 1.25f);
  const Eigen::Vector2f uv = c.project(p);
  EXPECT_NEAR(uv.x(), 100.0f, 1e-3);
  EXPECT_NEAR(uv.y(), 300.0f, 1e-3);
}

TEST(Camera, HandComputedDeprojection) {
  CameraIntrinsics c;
  c.width = 640;
  c.height = 480;
  c.fx = 500;
  c.fy = 400;
  c.cx = 320;
  c.cy = 240;
  const Eigen::Vector3f p = c.deproject(420.0f, 140.0f, 2.0f);
  EXPECT_FLOAT_EQ(p.x(), 0.4f);   // (420-320)/500*2
  EXPECT_FLOAT_EQ(p.y(), -0.5f);  // (140-240)/400*2
}

TEST(Camera, FovGivesExpectedFocal) {
  CameraIntrinsics c =
      CameraIntrinsics::from_fov(512, 424, 70.6 * std::numbers::pi / 180, 60.0 * std::numbers::pi / 180);
  EXPECT_NEAR(c.fx, 256.0 / std::tan(35.3 * std::numbers::pi / 180), 1e-9);
  EXPECT_NEAR(2 * std::atan(0.5 * c.height / c.fy), 60.0 * std::numbers::pi / 180, 1e-9);
}

TEST(Camera, ValidateRejectsBadValues) {
  CameraIntrinsics c = CameraIntrinsics::from_fov(10, 10, 1.0, 1.0);
  EXPECT_NO_THROW(c.validate("cam"));
  c.fx = -1;
  EXPECT_THROW(c.validate("cam"), cropsight::Error);
  c = CameraIntrinsics::from_fov(10, 10, 1.0, 1.0);
  c.depth_scale = NAN;
  try {
    c.validate("camera.yaml");
    FAIL();
  } catch (const cropsight::Error& e) {
    EXPECT_EQ(e.where(), "camera.yaml");
    EXPECT_NE(std::string(e.what()).find("depth_scale"), std::string::npos);
  }
}
