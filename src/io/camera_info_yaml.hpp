#pragma once
// ROS camera_info YAML (internal to io): what camera_calibration writes (image_width,
// image_height, camera_matrix{rows,cols,data}, distortion_model, distortion_coefficients, ...) and
// what `rostopic echo` prints of a sensor_msgs/CameraInfo (width, height, distortion_model, D, K,
// R, P, ...). read_camera_yaml (sequence.hpp) dispatches here when the file is one of these.
#include <yaml-cpp/yaml.h>

#include <string>

#include "cropsight/core/camera.hpp"

namespace cropsight::io::detail {

enum class CameraFileKind { Cropsight, RosCalibration, RosMessage, Unknown };

/// Which of the accepted camera files `root` (a YAML mapping) is, by its keys.
CameraFileKind camera_file_kind(const YAML::Node& root);

/// The intrinsics of a ROS camera_info mapping; depth_scale is REP 118's millimetres (0.001),
/// which no camera_info field carries. Throws Error(where, ...) for a missing or malformed key,
/// a camera matrix that is not 3x3, or a distortion model other than plumb_bob /
/// rational_polynomial (whose coefficients are OpenCV's order).
CameraIntrinsics camera_from_ros_yaml(const YAML::Node& root, CameraFileKind kind, const std::string& where);

/// The one-line list of accepted camera files, for the error on any other file.
const char* accepted_camera_files();

}  // namespace cropsight::io::detail
