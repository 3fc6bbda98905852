#pragma once
// Detection: one found crop instance in one frame.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "cropsight/core/geometry_types.hpp"

namespace cropsight {

struct Detection {
  float score = 0.0f;  ///< classifier score; higher = more confident (not necessarily a probability)
  int label = 0;       ///< class id (pipeline-specific; 1 = target crop)
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();  ///< metres, camera frame
  Box2D box;                                           ///< pixels
  std::vector<int> indices;                            ///< point indices in the frame's organised cloud (pixel indices)
  float size_m = 0.0f;                                 ///< diameter estimate, metres (0 = not measured)
  Eigen::Quaternionf orientation = Eigen::Quaternionf::Identity();  ///< camera frame
  int track_id = -1;                                                ///< -1 = not tracked
};

}  // namespace cropsight
