// PointCloud2 <-> buffers (ros/src/cloud_conversions.cpp): an organised cloud made from a depth
// frame gives that frame back (depth exact, intrinsics to float precision); clouds that are not
// a camera's organised cloud are an Error naming the topic; published clouds have the documented
// fields.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>

#include "cloud_conversions.hpp"
#include "cropsight/core/error.hpp"
#include "ros_test_support.hpp"

namespace cropsight::ros_io {
namespace {

using ros_test::error_of;

// A 40x30 frame of a tilted plane with a hole, colour a gradient.
bridge::FrameBuffers plane_frame() {
  bridge::FrameBuffers f;
  f.camera.width = 40;
  f.camera.height = 30;
  f.camera.fx = 52.5;
  f.camera.fy = 51.25;
  f.camera.cx = 19.3;
  f.camera.cy = 14.8;
  f.camera.depth_scale = 0.001;
  for (int v = 0; v < 30; ++v)
    for (int u = 0; u < 40; ++u) {
      const bool hole = u > 10 && u < 15 && v > 5 && v < 9;
      f.depth.push_back(hole ? 0 : std::uint16_t(900 + 7 * u + 3 * v));
      f.rgb.insert(f.rgb.end(), {std::uint8_t(6 * u), std::uint8_t(8 * v), 77});
    }
  return f;
}

TEST(CloudConversions, OrganisedCloudGivesItsDepthFrameBack) {
  const bridge::FrameBuffers f = plane_frame();
  const sensor_msgs::PointCloud2 pc = organised_cloud_from_frame(f);
  ASSERT_EQ(pc.width, 40u);
  ASSERT_EQ(pc.height, 30u);
  const bridge::FrameBuffers back = frame_from_organised_cloud(pc, 0.001, true, "/points");
  EXPECT_EQ(back.depth, f.depth);
  EXPECT_EQ(back.rgb, f.rgb);
  EXPECT_NEAR(back.camera.fx, f.camera.fx, 1e-4);
  EXPECT_NEAR(back.camera.fy, f.camera.fy, 1e-4);
  EXPECT_NEAR(back.camera.cx, f.camera.cx, 1e-4);
  EXPECT_NEAR(back.camera.cy, f.camera.cy, 1e-4);
  EXPECT_TRUE(frame_from_organised_cloud(pc, 0.001, false, "/points").rgb.empty());
}

TEST(CloudConversions, CloudsThatAreNotACamerasAreErrorsNamingTheTopic) {
  const sensor_msgs::PointCloud2 good = organised_cloud_from_frame(plane_frame());
  auto error = [&](const sensor_msgs::PointCloud2& pc, bool color = false) {
    return error_of([&] { frame_from_organised_cloud(pc, 0.001, color, "/cam/points"); });
  };
  sensor_msgs::PointCloud2 bad = good;
  bad.height = 1;
  bad.width = 1200;
  EXPECT_NE(error(bad).find("/cam/points: cloud is not organised"), std::string::npos) << error(bad);
  bad = good;
  bad.fields[2].name = "intensity";
  EXPECT_NE(error(bad).find("needs float32 fields x, y and z"), std::string::npos);
  bad = good;
  bad.data.resize(bad.data.size() - 1);
  EXPECT_NE(error(bad).find("data has"), std::string::npos);
  bad = good;
  bad.fields[3].offset = 14;
  EXPECT_NE(error(bad, true).find("lies outside point_step"), std::string::npos);
  bad = good;
  bad.fields.pop_back();
  EXPECT_NE(error(bad, true).find("no rgb or rgba field"), std::string::npos);
  // A cloud in a body frame (x forward, y left, z up: x' = z, y' = -x, z' = -y) instead of the
  // optical frame no longer projects onto its pixels.
  bad = good;
  for (std::size_t i = 0; i < std::size_t(bad.width) * bad.height; ++i) {
    float p[3], q[3];
    std::memcpy(p, bad.data.data() + i * bad.point_step, 12);
    q[0] = p[2], q[1] = -p[0], q[2] = -p[1];
    std::memcpy(bad.data.data() + i * bad.point_step, q, 12);
  }
  EXPECT_NE(error(bad).find("optical frame"), std::string::npos) << error(bad);
  // All NaN: nothing to fit.
  bridge::FrameBuffers empty = plane_frame();
  std::fill(empty.depth.begin(), empty.depth.end(), 0);
  EXPECT_NE(error(organised_cloud_from_frame(empty)).find("too few valid points"), std::string::npos);
}

TEST(CloudConversions, PublishedCloudsHaveTheDocumentedFields) {
  const std::vector<float> xyz{0.1f, 0.2f, 0.3f, -1, -2, 3};
  const std::vector<std::uint8_t> rgb{255, 0, 1, 2, 3, 4};
  const std::vector<int> labels{2, 5};
  const sensor_msgs::PointCloud2 pc = make_cloud(xyz, &rgb, &labels);
  ASSERT_EQ(pc.fields.size(), 5u);
  EXPECT_EQ(pc.fields[3].name, "rgb");
  EXPECT_EQ(pc.fields[4].name, "label");
  EXPECT_EQ(pc.fields[4].datatype, sensor_msgs::PointField::INT32);
  EXPECT_EQ(pc.point_step, 20u);
  EXPECT_EQ(pc.width, 2u);
  float y;
  std::memcpy(&y, pc.data.data() + 20 + 4, 4);
  EXPECT_EQ(y, -2.f);
  std::uint32_t packed;
  std::memcpy(&packed, pc.data.data() + 12, 4);
  EXPECT_EQ(packed, 0xFF0001u);
  std::int32_t label;
  std::memcpy(&label, pc.data.data() + 20 + 16, 4);
  EXPECT_EQ(label, 5);
  EXPECT_EQ(make_cloud(xyz).point_step, 12u);
}

}  // namespace
}  // namespace cropsight::ros_io
