#pragma once
// Pinhole camera intrinsics. Camera frame: x right, y down, z forward (depth), metres.
// Pixel (u, v): u = column, v = row; pixel centres at integer coordinates.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace cropsight {

struct CameraIntrinsics {
  int width = 0;
  int height = 0;
  double fx = 0, fy = 0;           ///< focal lengths, pixels
  double cx = 0, cy = 0;           ///< principal point, pixels
  double depth_scale = 0.001;      ///< metres per raw depth unit
  std::vector<double> distortion;  ///< optional OpenCV-order coefficients (k1 k2 p1 p2 [k3...])
  std::string sensor;              ///< free text, e.g. "kinect-v2"

  /// 3D point (camera frame, m) of pixel (u, v) at depth z (m).
  Eigen::Vector3f deproject(float u, float v, float z) const {
    return {float((u - cx) / fx) * z, float((v - cy) / fy) * z, z};
  }
  /// Pixel coordinates of a camera-frame point with p.z() > 0.
  Eigen::Vector2f project(const Eigen::Vector3f& p) const {
    return {float(fx * p.x() / p.z() + cx), float(fy * p.y() / p.z() + cy)};
  }
  bool contains(float u, float v) const { return u >= 0 && v >= 0 && u <= width - 1 && v <= height - 1; }

  /// Intrinsics from image size and full fields of view (radians), principal point centred.
  static CameraIntrinsics from_fov(int width, int height, double hfov_rad, double vfov_rad);

  /// Throws cropsight::Error(where, ...) when a field is out of range (size, focal, scale).
  void validate(const std::string& where) const;
};

}  // namespace cropsight
