#pragma once
// Camera → field transform for a camera that looks straight down at the crop.
//
// Camera frame (cropsight convention): x right, y down in the image, z forward (= towards the
// ground for a downward camera). Field frame: right-handed, metres, fixed to the field; the camera
// translates in it (no rotation: a tractor-mounted camera keeps its attitude along a row).
//
//   p_field = x_c + R · p_camera
//
// where x_c is the camera position in the field frame and R a signed axis permutation written as
// three axis names, one per field axis. The default "y,x,-z" is the simulator's frame
// (include/cropsight/sim/renderer.hpp: field x along the row = camera y, field y across the row =
// camera x, field z up = −camera z; the tractor drives along +x, which moves down the image).
// "x,-y,-z" would instead put field X along the image's x axis. R must be a proper rotation
// (determinant +1).
#include <Eigen/Core>
#include <string>

namespace cropsight::tracking {

struct FieldTransform {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  ///< R: camera axes → field axes

  /// Parses "x,-y,-z" style text; throws Error(where, ...) for anything that is not a proper
  /// signed permutation.
  static FieldTransform parse(const std::string& text, const std::string& where = "tracking.camera_to_field");

  Eigen::Vector3d to_field(const Eigen::Vector3d& camera_position, const Eigen::Vector3f& p_camera) const {
    return camera_position + rotation * p_camera.cast<double>();
  }
  Eigen::Vector3d to_camera(const Eigen::Vector3d& camera_position, const Eigen::Vector3d& p_field) const {
    return rotation.transpose() * (p_field - camera_position);
  }
};

}  // namespace cropsight::tracking
