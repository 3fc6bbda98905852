// libFuzzer harness: the ROS messages a node converts (ros/src/ros_conversions.*,
// cloud_conversions.*, the grape node's boxes), with every field a publisher controls filled from
// the fuzzer's bytes: camera_info + depth + colour images as the broccoli, potato and grape nodes
// assemble a frame; an organised PointCloud2 as the broccoli node's ~input:=cloud reads it; a
// Detection2DArray as the grape node's `detections`. Each conversion must succeed or throw
// cropsight::Error (the node then skips the message and counts it).
//
// ROS's own deserializer is not fuzzed: roscpp runs it before a callback sees a message, and
// it is not cropsight's code. Sizes are drawn mostly small (so that images can be valid) and
// sometimes anywhere in uint32 (so that a size the data cannot hold is tried). C++17, like ros/.
#include <fuzzer/FuzzedDataProvider.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>
#include <vision_msgs/Detection2DArray.h>

#include "cloud_conversions.hpp"
#include "fuzz_support.hpp"
#include "grape_node.hpp"
#include "ros_conversions.hpp"

namespace {

std::uint32_t dimension(FuzzedDataProvider& in) {
  return in.ConsumeBool() ? in.ConsumeIntegralInRange<std::uint32_t>(0, 40) : in.ConsumeIntegral<std::uint32_t>();
}

std::string one_of(FuzzedDataProvider& in, std::initializer_list<const char*> names) {
  const std::size_t k = in.ConsumeIntegralInRange<std::size_t>(0, names.size());
  return k < names.size() ? std::string(*(names.begin() + k)) : in.ConsumeRandomLengthString(16);
}

sensor_msgs::Image image(FuzzedDataProvider& in, std::initializer_list<const char*> encodings) {
  sensor_msgs::Image im;
  im.width = dimension(in);
  im.height = dimension(in);
  im.encoding = one_of(in, encodings);
  im.is_bigendian = in.ConsumeIntegral<std::uint8_t>();
  im.step = in.ConsumeBool() ? im.width * in.ConsumeIntegralInRange<std::uint32_t>(0, 5)
                             : in.ConsumeIntegral<std::uint32_t>();
  im.data = in.ConsumeBytes<std::uint8_t>(in.ConsumeIntegralInRange<std::size_t>(0, 1 << 15));
  return im;
}

void camera_and_images(FuzzedDataProvider& in) {
  sensor_msgs::CameraInfo info;
  info.width = dimension(in);
  info.height = dimension(in);
  for (double& k : info.K)
    k = in.ConsumeBool() ? in.ConsumeFloatingPointInRange<double>(-100, 1000) : in.ConsumeFloatingPoint<double>();
  info.distortion_model = one_of(in, {"plumb_bob", "rational_polynomial", "equidistant"});
  info.D.resize(in.ConsumeIntegralInRange<std::size_t>(0, 14));
  for (double& d : info.D) d = in.ConsumeFloatingPoint<double>();
  const double depth_scale = in.ConsumeBool() ? 0.001 : in.ConsumeFloatingPoint<double>();
  const sensor_msgs::Image depth = image(in, {"16UC1", "mono16", "32FC1", "bgr8"});
  const sensor_msgs::Image color = image(in, {"rgb8", "bgr8", "rgba8", "bgra8", "mono8", "16UC1"});
  cropsight::fuzz::expect_error_or_success("camera_info + images", [&] {
    const auto cam = cropsight::ros_io::camera_from_info(info, depth_scale, "info");
    (void)cropsight::ros_io::depth_from_image(depth, cam, "depth");
    (void)cropsight::ros_io::rgb_from_image(color, cam, "color");
  });
}

void organised_cloud(FuzzedDataProvider& in) {
  sensor_msgs::PointCloud2 pc;
  pc.width = dimension(in);
  pc.height = dimension(in);
  pc.fields.resize(in.ConsumeIntegralInRange<std::size_t>(0, 6));
  for (auto& f : pc.fields) {
    f.name = one_of(in, {"x", "y", "z", "rgb", "rgba"});
    f.offset = in.ConsumeBool() ? in.ConsumeIntegralInRange<std::uint32_t>(0, 32) : in.ConsumeIntegral<std::uint32_t>();
    f.datatype = in.ConsumeBool() ? sensor_msgs::PointField::FLOAT32 : in.ConsumeIntegral<std::uint8_t>();
    f.count = in.ConsumeIntegral<std::uint32_t>();
  }
  pc.is_bigendian = in.ConsumeBool();
  pc.point_step =
      in.ConsumeBool() ? in.ConsumeIntegralInRange<std::uint32_t>(0, 32) : in.ConsumeIntegral<std::uint32_t>();
  pc.row_step = in.ConsumeBool() ? pc.point_step * pc.width : in.ConsumeIntegral<std::uint32_t>();
  const double depth_scale = in.ConsumeBool() ? 0.001 : in.ConsumeFloatingPoint<double>();
  const bool want_color = in.ConsumeBool();
  pc.data = in.ConsumeRemainingBytes<std::uint8_t>();
  cropsight::fuzz::expect_error_or_success("organised cloud", [&] {
    const auto frame = cropsight::ros_io::frame_from_organised_cloud(pc, depth_scale, want_color, "points");
    (void)cropsight::ros_io::organised_cloud_from_frame(frame);
  });
}

void grape_boxes(FuzzedDataProvider& in) {
  vision_msgs::Detection2DArray arr;
  arr.detections.resize(in.ConsumeIntegralInRange<std::size_t>(0, 8));
  for (auto& d : arr.detections) {
    d.results.resize(in.ConsumeIntegralInRange<std::size_t>(0, 2));
    for (auto& r : d.results) {
      r.id = in.ConsumeBool() ? in.ConsumeIntegralInRange<std::int64_t>(0, 3) : in.ConsumeIntegral<std::int64_t>();
      r.score = in.ConsumeFloatingPoint<double>();
    }
    for (double* v : {&d.bbox.center.x, &d.bbox.center.y, &d.bbox.size_x, &d.bbox.size_y})
      *v = in.ConsumeBool() ? in.ConsumeFloatingPointInRange<double>(-10, 2000) : in.ConsumeFloatingPoint<double>();
  }
  cropsight::fuzz::expect_error_or_success("detections",
                                           [&] { (void)cropsight::ros_io::grape_boxes(arr, "detections"); });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  switch (in.ConsumeIntegralInRange<int>(0, 2)) {
    case 0:
      camera_and_images(in);
      break;
    case 1:
      organised_cloud(in);
      break;
    default:
      grape_boxes(in);
  }
  return 0;
}
