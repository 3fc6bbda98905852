#pragma once
// A labelled or proposed head's size from its pixels and the frame's depth (internal to
// src/studio): what the page shows beside a candidate and what groundtruth.json records.
#include <Eigen/Core>
#include <vector>

#include "cropsight/core/camera.hpp"
#include "cropsight/core/image.hpp"

namespace cropsight::studio {

struct HeadGeometry {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  ///< camera frame, metres (measured pixels)
  double diameter_mm = 0.0;  ///< of the disc of the measured area: each pixel covers (z/fx)·(z/fy) m²
  int measured = 0;          ///< pixels with depth
};

/// `pixels`: row-major indices into `depth` (raw units, camera.depth_scale metres each).
HeadGeometry head_geometry(const std::vector<int>& pixels, const DepthImage& depth, const CameraIntrinsics& camera);

}  // namespace cropsight::studio
