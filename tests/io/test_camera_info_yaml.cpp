// Intrinsics from a ROS camera_info YAML, beside cropsight's camera.yaml (read_camera_yaml).
#include <gtest/gtest.h>

#include "cropsight/core/error.hpp"
#include "cropsight/io/sequence.hpp"
#include "testing/testing.hpp"

namespace cropsight::io {
namespace {

using cropsight::testing::error_message;
using cropsight::testing::TempDir;
using cropsight::testing::write_text;

// What camera_calibration writes (ost.yaml), for a Kinect v2's depth camera.
const char* kCalibrationYaml = R"(image_width: 512
image_height: 424
camera_name: kinect2_ir
camera_matrix:
  rows: 3
  cols: 3
  data: [365.5, 0, 256.2, 0, 364.9, 205.1, 0, 0, 1]
distortion_model: plumb_bob
distortion_coefficients:
  rows: 1
  cols: 5
  data: [0.09, -0.27, 0.001, -0.002, 0.1]
rectification_matrix:
  rows: 3
  cols: 3
  data: [1, 0, 0, 0, 1, 0, 0, 0, 1]
projection_matrix:
  rows: 3
  cols: 4
  data: [365.5, 0, 256.2, 0, 0, 364.9, 205.1, 0, 0, 0, 1, 0]
)";

// A sensor_msgs/CameraInfo as `rostopic echo -n 1 /camera/depth/camera_info` prints it.
const char* kMessageYaml = R"(header:
  seq: 12
  stamp:
    secs: 1596203844
    nsecs: 123000000
  frame_id: "camera_depth_optical_frame"
height: 480
width: 640
distortion_model: "plumb_bob"
D: [0.0, 0.0, 0.0, 0.0, 0.0]
K: [383.2, 0.0, 320.1, 0.0, 383.2, 241.7, 0.0, 0.0, 1.0]
R: [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
P: [383.2, 0.0, 320.1, 0.0, 0.0, 383.2, 241.7, 0.0, 0.0, 0.0, 1.0, 0.0]
binning_x: 0
binning_y: 0
roi:
  x_offset: 0
  y_offset: 0
  height: 0
  width: 0
  do_rectify: False
---
)";

TEST(CameraInfoYaml, CalibrationFile) {
  TempDir t;
  write_text(t / "ost.yaml", kCalibrationYaml);
  const CameraIntrinsics c = read_camera_yaml(t / "ost.yaml");
  EXPECT_EQ(c.width, 512);
  EXPECT_EQ(c.height, 424);
  EXPECT_DOUBLE_EQ(c.fx, 365.5);
  EXPECT_DOUBLE_EQ(c.fy, 364.9);
  EXPECT_DOUBLE_EQ(c.cx, 256.2);
  EXPECT_DOUBLE_EQ(c.cy, 205.1);
  EXPECT_DOUBLE_EQ(c.depth_scale, 0.001);  // REP 118
  EXPECT_EQ(c.distortion, (std::vector<double>{0.09, -0.27, 0.001, -0.002, 0.1}));
  EXPECT_EQ(c.sensor, "kinect2_ir");
}

TEST(CameraInfoYaml, RostopicEchoMessage) {
  TempDir t;
  write_text(t / "info.yaml", kMessageYaml);
  const CameraIntrinsics c = read_camera_yaml(t / "info.yaml");
  EXPECT_EQ(c.width, 640);
  EXPECT_EQ(c.height, 480);
  EXPECT_DOUBLE_EQ(c.fx, 383.2);
  EXPECT_DOUBLE_EQ(c.cy, 241.7);
  EXPECT_EQ(c.distortion.size(), 5u);
}

// Every bad file is one Error naming the file and the problem.
TEST(CameraInfoYaml, BadFiles) {
  TempDir t;
  auto error_of = [&](const std::string& text) {
    write_text(t / "c.yaml", text);
    return error_message([&] { read_camera_yaml(t / "c.yaml"); });
  };
  std::string zero_focal = kCalibrationYaml;
  zero_focal.replace(zero_focal.find("365.5, 0, 256.2"), 5, "0");
  EXPECT_NE(error_of(zero_focal).find("focal lengths fx, fy must be finite and positive"), std::string::npos);
  std::string short_matrix = kMessageYaml;
  short_matrix.replace(short_matrix.find("K: [383.2, "), 11, "K: [");
  EXPECT_NE(error_of(short_matrix).find("9 numbers"), std::string::npos);
  std::string fisheye = kCalibrationYaml;
  fisheye.replace(fisheye.find("plumb_bob"), 9, "equidistant");
  EXPECT_NE(error_of(fisheye).find("'equidistant' is not supported"), std::string::npos);
  std::string no_width = kCalibrationYaml;
  no_width.erase(0, no_width.find('\n') + 1);
  EXPECT_NE(error_of(no_width).find("missing required key 'image_width'"), std::string::npos);
  // Neither format: the line names the accepted ones.
  const std::string unknown = error_of("focal: 500\nsize: [640, 480]\n");
  EXPECT_NE(unknown.find((t / "c.yaml").string()), std::string::npos);
  EXPECT_NE(unknown.find("camera_info"), std::string::npos);
  EXPECT_NE(unknown.find("camera.yaml"), std::string::npos);
  EXPECT_EQ(unknown.find('\n'), std::string::npos);
}

}  // namespace
}  // namespace cropsight::io
