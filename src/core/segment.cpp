#include "cropsight/core/segment.hpp"

#include <algorithm>
#include <limits>

#include "cropsight/core/organized_cloud.hpp"

namespace cropsight {

void summarize(Segment& s, const OrganizedCloud& cloud) {
  if (s.indices.empty()) {
    s.centroid.setZero();
    s.min.setZero();
    s.max.setZero();
    s.box = {};
    return;
  }
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(std::numeric_limits<float>::max());
  Eigen::Vector3f hi = -lo;
  int u0 = cloud.width, v0 = cloud.height, u1 = -1, v1 = -1;
  for (int i : s.indices) {
    const Eigen::Vector3f p = cloud.point(std::size_t(i));
    sum += p.cast<double>();
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
    const int u = i % cloud.width, v = i / cloud.width;
    u0 = std::min(u0, u);
    v0 = std::min(v0, v);
    u1 = std::max(u1, u);
    v1 = std::max(v1, v);
  }
  s.centroid = (sum / double(s.indices.size())).cast<float>();
  s.min = lo;
  s.max = hi;
  s.box = {u0, v0, u1 - u0 + 1, v1 - v0 + 1};
}

}  // namespace cropsight
