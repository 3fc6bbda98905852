#pragma once
// sensor_msgs/PointCloud2 <-> the bridge's buffers: the clouds the nodes publish (seedling points,
// labelled grape bunches) and the organised clouds the broccoli node takes as input.
#include <sensor_msgs/PointCloud2.h>

#include <cstdint>
#include <string>
#include <vector>

#include "cropsight/bridge/frame_buffers.hpp"
#include "cropsight/core/cloud.hpp"

namespace cropsight::ros_io {

/// An unorganised cloud (height 1) with fields x y z (float32, m), then rgb (float32 holding
/// 0x00RRGGBB, PCL's packing) when `rgb` is given (3 per point), then label (int32) when
/// `labels` is given (1 per point). `xyz` holds 3 floats per point.
sensor_msgs::PointCloud2 make_cloud(const std::vector<float>& xyz, const std::vector<std::uint8_t>* rgb = nullptr,
                                    const std::vector<int>* labels = nullptr);

/// A library Cloud (m; colours r, g, b in [0, 1]) flattened for make_cloud, appended to what `out`
/// holds: colours as round(clamp(c, 0, 1) x 255), black for a cloud without colours; label 0 for a
/// cloud without labels.
struct FlatCloud {
  std::vector<float> xyz;         ///< 3 per point, m
  std::vector<std::uint8_t> rgb;  ///< 3 per point
  std::vector<int> labels;        ///< 1 per point
};
void append_cloud(const Cloud& cloud, FlatCloud& out);

/// The organised cloud of a depth frame, as depth_image_proc/point_cloud_xyz(rgb) makes it: one
/// point per pixel, x = (u - cx) z / fx, y = (v - cy) z / fy, z = depth x depth_scale (float32, m;
/// NaN where the depth is 0), and an rgb field (PCL's packing) when the frame has colour. The
/// camera's distortion is ignored, as depth_image_proc does. is_dense is false.
sensor_msgs::PointCloud2 organised_cloud_from_frame(const bridge::FrameBuffers& frame);

/// An organised cloud (height > 1, one point per pixel, camera optical frame: x right, y down,
/// z forward, metres; what depth_image_proc/point_cloud_xyz(rgb) publishes) as a depth frame:
/// depth = z / depth_scale rounded (NaN, inf or z <= 0: 0 = no return), colour from an `rgb` or
/// `rgba` field when `want_color`, and the pinhole intrinsics fitted to the points (least squares
/// of u = fx x/z + cx and v = fy y/z + cy; exact for a cloud made from a depth image). Throws
/// Error(topic, problem) for an unorganised cloud, missing or non-float32 x/y/z fields, a
/// data size that disagrees with the layout, too few valid points to fit the intrinsics (fewer
/// than 3 columns or rows with a point) or a fit that is not a pinhole camera (fx or fy <= 0).
bridge::FrameBuffers frame_from_organised_cloud(const sensor_msgs::PointCloud2& cloud, double depth_scale,
                                                bool want_color, const std::string& topic);

}  // namespace cropsight::ros_io
