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
// three axis names, one per field axis: "x,-y,-z" (default) means field X = camera x, field
// Y = −camera y, field Z = −camera z (Z up, the ground plane is X–Y). R must be a proper rotation
// (determinant +1). The simulator's field frame (docs/simulator.md) uses the same default.
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
