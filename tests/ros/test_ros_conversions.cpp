// sensor_msgs -> buffers (ros/src/ros_conversions.cpp): every malformed field a publisher can get
// wrong is an Error naming the topic, and the good encodings convert exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "cropsight/core/error.hpp"
#include "ros_conversions.hpp"
#include "ros_test_support.hpp"

namespace cropsight::ros_io {
namespace {

using ros_test::error_of;

bridge::CameraModel camera(int w, int h) {
  bridge::CameraModel c;
  c.width = w;
  c.height = h;
  c.fx = c.fy = 100;
  c.cx = w / 2.0;
  c.cy = h / 2.0;
  return c;
}

TEST(RosConversions, Depth16uc1RoundTripsWithPaddedRows) {
  const auto cam = camera(3, 2);
  const std::vector<std::uint16_t> d{1, 2, 3, 400, 500, 65535};
  sensor_msgs::Image im = image_from_depth(d, 3, 2);
  EXPECT_EQ(depth_from_image(im, cam, "t"), d);
  // Rows padded to 8 bytes, as some drivers do.
  sensor_msgs::Image padded = im;
  padded.step = 8;
  padded.data.assign(16, 0);
  for (int v = 0; v < 2; ++v) std::memcpy(padded.data.data() + 8 * v, im.data.data() + 6 * v, 6);
  EXPECT_EQ(depth_from_image(padded, cam, "t"), d);
  // Big-endian rows are swapped.
  sensor_msgs::Image be = im;
  be.is_bigendian = 1;
  for (std::size_t i = 0; i < be.data.size(); i += 2) std::swap(be.data[i], be.data[i + 1]);
  EXPECT_EQ(depth_from_image(be, cam, "t"), d);
}

TEST(RosConversions, Depth32fc1MetresBecomeRawUnitsAndNanIsNoReturn) {
  auto cam = camera(4, 1);
  cam.depth_scale = 0.001;
  const float m[4] = {1.2344f, std::nanf(""), -1.f, INFINITY};
  sensor_msgs::Image im;
  im.width = 4;
  im.height = 1;
  im.encoding = "32FC1";
  im.step = 16;
  im.data.resize(16);
  std::memcpy(im.data.data(), m, 16);
  EXPECT_EQ(depth_from_image(im, cam, "t"), (std::vector<std::uint16_t>{1234, 0, 0, 0}));
}

TEST(RosConversions, ColourEncodingsGiveRgb) {
  const auto cam = camera(1, 1);
  sensor_msgs::Image im;
  im.width = im.height = 1;
  im.step = 3;
  im.data = {10, 20, 30};
  im.encoding = "rgb8";
  EXPECT_EQ(rgb_from_image(im, cam, "t"), (std::vector<std::uint8_t>{10, 20, 30}));
  im.encoding = "bgr8";
  EXPECT_EQ(rgb_from_image(im, cam, "t"), (std::vector<std::uint8_t>{30, 20, 10}));
  im.encoding = "bgra8";
  im.step = 4;
  im.data = {30, 20, 10, 255};
  EXPECT_EQ(rgb_from_image(im, cam, "t"), (std::vector<std::uint8_t>{10, 20, 30}));
}

TEST(RosConversions, MalformedImagesNameTheTopicAndTheProblem) {
  const auto cam = camera(3, 2);
  sensor_msgs::Image im = image_from_depth(std::vector<std::uint16_t>(6, 1), 3, 2);
  sensor_msgs::Image wrong = im;
  wrong.encoding = "bgr8";
  EXPECT_NE(error_of([&] { depth_from_image(wrong, cam, "/cam/depth"); }).find("/cam/depth: depth encoding 'bgr8'"),
            std::string::npos);
  wrong = im;
  wrong.width = 4;
  EXPECT_NE(error_of([&] { depth_from_image(wrong, cam, "/d"); }).find("image is 4x2, camera_info says 3x2"),
            std::string::npos);
  wrong = im;
  wrong.data.resize(5);
  EXPECT_NE(error_of([&] { depth_from_image(wrong, cam, "/d"); }).find("data has 5 bytes"), std::string::npos);
  wrong = im;
  wrong.step = 2;
  EXPECT_NE(error_of([&] { depth_from_image(wrong, cam, "/d"); }).find("shorter than a row"), std::string::npos);
  sensor_msgs::Image colour = image_from_rgb(std::vector<std::uint8_t>(18, 0), 3, 2);
  colour.encoding = "yuv422";
  EXPECT_NE(error_of([&] { rgb_from_image(colour, cam, "/c"); }).find("/c: colour encoding 'yuv422'"),
            std::string::npos);
}

TEST(RosConversions, CameraInfoIsValidatedAndRoundTrips) {
  auto cam = camera(640, 480);
  cam.distortion = {0.1, -0.2, 0.001, 0.002, 0.05};
  const sensor_msgs::CameraInfo info = info_from_camera(cam);
  const bridge::CameraModel back = camera_from_info(info, 0.001, "t");
  EXPECT_EQ(back.width, 640);
  EXPECT_EQ(back.fx, cam.fx);
  EXPECT_EQ(back.cy, cam.cy);
  EXPECT_EQ(back.distortion, cam.distortion);
  sensor_msgs::CameraInfo bad = info;
  bad.K[0] = 0;
  EXPECT_NE(error_of([&] { camera_from_info(bad, 0.001, "/info"); }).find("/info: camera_info K has a focal length"),
            std::string::npos);
  bad = info;
  bad.K[2] = std::nan("");
  EXPECT_NE(error_of([&] { camera_from_info(bad, 0.001, "/info"); }).find("non-finite"), std::string::npos);
  bad = info;
  bad.width = 0;
  EXPECT_NE(error_of([&] { camera_from_info(bad, 0.001, "/info"); }).find("is not an image size"), std::string::npos);
}

TEST(RosConversions, AHugeCameraInfoWithASmallImageIsAnErrorBeforeAnyAllocation) {
  // camera_info may claim up to 100000 x 100000 pixels; the depth buffer was allocated (20 GB)
  // before the image's size and encoding were checked, so a malformed pair could exhaust memory
  // (std::bad_alloc escaping the node's callback). Now the image is checked first.
  bridge::CameraModel cam = camera(100000, 100000);
  const sensor_msgs::Image small = image_from_depth({1, 2, 3, 4}, 2, 2);
  EXPECT_NE(
      error_of([&] { depth_from_image(small, cam, "/d"); }).find("/d: image is 2x2, camera_info says 100000x100000"),
      std::string::npos);
  sensor_msgs::Image wrong = small;
  wrong.encoding = "bgr8";
  EXPECT_NE(error_of([&] { depth_from_image(wrong, cam, "/d"); }).find("depth encoding 'bgr8'"), std::string::npos);
}

}  // namespace
}  // namespace cropsight::ros_io
