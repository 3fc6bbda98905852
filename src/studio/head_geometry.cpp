// A head's centroid and disc diameter from its pixels (head_geometry.hpp).
#include "studio/head_geometry.hpp"

#include <cmath>
#include <numbers>

namespace cropsight::studio {

HeadGeometry head_geometry(const std::vector<int>& pixels, const DepthImage& depth, const CameraIntrinsics& cam) {
  HeadGeometry g;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double area = 0.0;
  for (int p : pixels) {
    const double z = double(depth.data[std::size_t(p)]) * cam.depth_scale;
    if (z <= 0) continue;
    sum += cam.deproject(float(p % depth.width), float(p / depth.width), float(z)).cast<double>();
    area += (z / cam.fx) * (z / cam.fy);
    ++g.measured;
  }
  if (g.measured > 0) g.centroid = sum / g.measured;
  g.diameter_mm = 2000.0 * std::sqrt(area / std::numbers::pi);
  return g;
}

}  // namespace cropsight::studio
