#pragma once
// Disparity → 3D points in the rectified left camera frame (x right, y down, z forward, metres):
// Z = f B / d, X = (u - cx) Z / f, Y = (v - cy) Z / f. Pixels without a disparity (NaN, <= 0) and
// points outside [min_depth, max_depth] are removed.
#include <Eigen/Core>
#include <vector>

#include "cropsight/stereo/disparity.hpp"
#include "cropsight/stereo/rectification.hpp"

namespace cropsight::stereo {

struct StereoPoints {
  std::vector<Eigen::Vector3f> points;  ///< m, rectified left camera frame
  std::vector<int> pixels;              ///< row-major left-image index of each point
};

StereoPoints reconstruct(const DisparityImage& disparity, const RectifiedGeometry& geometry, double min_depth = 0.0,
                         double max_depth = 1e9);

}  // namespace cropsight::stereo
