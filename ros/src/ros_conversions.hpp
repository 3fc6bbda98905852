#pragma once
// sensor_msgs <-> the bridge's plain buffers. Every reader validates what a malformed message can
// get wrong (encoding, size, step, camera values) and throws cropsight::Error(topic, problem).
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include <string>

#include "cropsight/bridge/frame_buffers.hpp"

namespace cropsight::ros_io {

/// Intrinsics of a CameraInfo (K; D when the model is plumb_bob or rational_polynomial).
/// depth_scale is not in CameraInfo: the caller's (metres per raw 16UC1 unit).
bridge::CameraModel camera_from_info(const sensor_msgs::CameraInfo& info, double depth_scale, const std::string& topic);
sensor_msgs::CameraInfo info_from_camera(const bridge::CameraModel& camera);

/// Depth in the camera's raw units: 16UC1 / mono16 copied; 32FC1 metres divided by depth_scale
/// and rounded (NaN, inf and <= 0 become 0 = no return). The size must be the camera's.
std::vector<std::uint16_t> depth_from_image(const sensor_msgs::Image& image, const bridge::CameraModel& camera,
                                            const std::string& topic);
/// Colour as R G B: rgb8, bgr8, rgba8, bgra8 (and mono8, repeated). The size must be the camera's.
std::vector<std::uint8_t> rgb_from_image(const sensor_msgs::Image& image, const bridge::CameraModel& camera,
                                         const std::string& topic);

sensor_msgs::Image image_from_depth(const std::vector<std::uint16_t>& depth, int width, int height);
sensor_msgs::Image image_from_rgb(const std::vector<std::uint8_t>& rgb, int width, int height);

}  // namespace cropsight::ros_io
