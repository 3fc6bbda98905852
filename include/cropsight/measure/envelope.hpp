#pragma once
// The seedling paper's envelope box of a plant's points, defined once for the seedling pipeline and the
// simulator's ground truth (inline here so that both use the very same definition; its PCA is
// geometry/pca, which the simulator links).
//   height: largest distance of a point above the soil plane n . x + d = 0 (n unit, pointing up);
//   length, width: extents of the points projected on the plane along their two principal axes
//   (length >= width); volume = length * width * height.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <vector>

#include "cropsight/geometry/pca.hpp"

namespace cropsight::measure {

struct EnvelopeBox {
  double length = 0, width = 0, height = 0;                  ///< m
  double volume() const { return length * width * height; }  ///< m^3
};

inline EnvelopeBox envelope_box(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& n, double d) {
  EnvelopeBox box;
  if (points.size() < 2) return box;
  const Eigen::Vector3d e1 = n.unitOrthogonal(), e2 = n.cross(e1);
  std::vector<Eigen::Vector2d> q;
  q.reserve(points.size());
  for (const auto& p : points) {
    box.height = std::max(box.height, n.dot(p) + d);
    q.emplace_back(e1.dot(p), e2.dot(p));
  }
  const auto pc = geometry::principal_axes(geometry::point_moments(q).scatter);
  const Eigen::Vector2d a = pc.major(), b = pc.normal();  // major and minor axis
  double amin = 1e300, amax = -1e300, bmin = 1e300, bmax = -1e300;
  for (const auto& v : q) {
    amin = std::min(amin, a.dot(v)), amax = std::max(amax, a.dot(v));
    bmin = std::min(bmin, b.dot(v)), bmax = std::max(bmax, b.dot(v));
  }
  box.length = std::max(amax - amin, bmax - bmin);
  box.width = std::min(amax - amin, bmax - bmin);
  return box;
}

}  // namespace cropsight::measure
