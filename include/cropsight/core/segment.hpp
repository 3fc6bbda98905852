#pragma once
// Segment: a set of point indices into a cloud (organised or not) plus a cheap summary.
#include <Eigen/Core>
#include <vector>

#include "cropsight/core/geometry_types.hpp"

namespace cropsight {

struct OrganizedCloud;

struct Segment {
  std::vector<int> indices;                                                      ///< indices into the source cloud
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();                            ///< metres, source cloud frame
  Eigen::Vector3f min = Eigen::Vector3f::Zero(), max = Eigen::Vector3f::Zero();  ///< 3D AABB, metres
  Box2D box;  ///< pixel box (organised sources only; empty otherwise)

  std::size_t size() const { return indices.size(); }
};

/// Fills centroid, 3D bounds and pixel box of `s` from `cloud` (indices must be valid points).
void summarize(Segment& s, const OrganizedCloud& cloud);

}  // namespace cropsight
