#pragma once
// Colour from a second camera registered to depth: recorders that keep the streams unaligned (a
// Kinect v2's 1920x1080 colour beside its 512x424 depth, a RealSense without align) give colour
// of another size, seen from a point a few centimetres away. Each depth pixel is deprojected
// (depth intrinsics), moved into the colour camera (depth-to-colour extrinsics), projected
// (colour intrinsics, with their plumb_bob distortion) and takes the colour of the nearest colour
// pixel; a depth pixel hidden from the colour camera by a nearer surface, outside its image or
// without depth gets black (0, 0, 0). This is the projection of OpenCV's cv::rgbd::registerDepth,
// run the other way (a test checks the two agree).
#include <Eigen/Core>
#include <filesystem>

#include "cropsight/core/camera.hpp"
#include "cropsight/core/image.hpp"

namespace cropsight::io {

/// A point's coordinates in the colour camera: p_color = rotation * p_depth + translation
/// (metres, both camera frames x right, y down, z forward).
struct DepthToColor {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
};

/// Reads an extrinsics YAML: a mapping `depth_to_color:` (or `color_to_depth:`, inverted here)
/// with `rotation` (9 numbers, row-major) and `translation` (3 numbers, metres). Throws
/// Error(path, ...) for a missing key, a wrong count, a non-finite number or a rotation that is
/// not one (R^T R = I and det R = 1 within 1e-3).
DepthToColor read_extrinsics_yaml(const std::filesystem::path& path);

/// The colour image resampled onto the depth image's pixels (same size as `depth`).
/// `depth_camera` gives the depth image's intrinsics and depth_scale; `color_camera` the colour
/// image's (its size must match `color`).
ColorImage register_color(const DepthImage& depth, const CameraIntrinsics& depth_camera, const ColorImage& color,
                          const CameraIntrinsics& color_camera, const DepthToColor& extrinsics);

}  // namespace cropsight::io
