#pragma once
// Where one 2D detection is in 3D (measure::locate, position.hpp): plain C++17 data, so that the
// potato pipeline's results reach the ROS nodes (built as C++17) as they are. Camera frame: x
// right, y down, z forward, metres.
#include <Eigen/Core>

namespace cropsight::measure {

/// Where one detection is.
struct Position3D {
  Eigen::Vector3f xyz = Eigen::Vector3f::Zero();  ///< camera frame, m (the centre or the surface point)
  float surface_depth_m = 0;                      ///< depth read at the box centre, m (0 = none)
  float width_m = 0, height_m = 0;                ///< box sides at the potato's depth, m
  float area_m2 = 0;                              ///< width_m * height_m
  int valid_pixels = 0, window_pixels = 0;        ///< depth samples used / window size
  int silhouette_pixels = 0;                      ///< box pixels of the silhouette (centre_offset silhouette)
  float minor_m = 0, major_m = 0;                 ///< silhouette's equivalent-ellipse full axes at the centre depth, m
  float thickness_m = 0;       ///< full axis along the view fitted by centre_offset profile, m (0 = not fitted)
  bool depth_ok = false;       ///< depth inside [min, max] from enough valid pixels
  bool cut_by_border = false;  ///< the box touches the image border: part of the potato is out of view, so
                               ///< its centre (box or silhouette) is off toward the image inside
};

}  // namespace cropsight::measure
