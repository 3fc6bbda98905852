#pragma once
// Plain frame buffers for callers that cannot include the C++20 library headers: the ROS nodes
// and bag tools are a C++17 target, because Debian's ROS 1 message headers do not compile as
// C++20 (std::allocator<void>::rebind was removed). Every header under cropsight/bridge/ is
// valid C++17 and holds only standard types; the implementation (src/bridge/) is C++20.
//
// Pixels are row-major, origin top-left; the camera frame is x right, y down, z forward, metres.
#include <cstdint>
#include <string>
#include <vector>

namespace cropsight::bridge {

/// Pinhole intrinsics of the depth image (colour is registered to it).
struct CameraModel {
  int width = 0, height = 0;
  double fx = 0, fy = 0;           ///< pixels
  double cx = 0, cy = 0;           ///< pixels
  double depth_scale = 0.001;      ///< metres per raw depth unit
  std::vector<double> distortion;  ///< OpenCV order (k1 k2 p1 p2 [k3 ...]); may be empty
  std::string sensor;              ///< free text, e.g. "kinect-v2"
};

/// One RGB-D frame as raw buffers.
struct FrameBuffers {
  int index = 0;           ///< frame number in its sequence (0-based)
  double timestamp = 0.0;  ///< s
  CameraModel camera;
  std::vector<std::uint16_t> depth;  ///< width*height raw units (metres = value * depth_scale); 0 = no return
  std::vector<std::uint8_t> rgb;     ///< width*height*3, R G B; empty when there is no colour
  bool has_camera_position = false;
  double camera_position[3] = {0, 0, 0};  ///< field frame, m (the sequence's poses.csv)
};

}  // namespace cropsight::bridge
