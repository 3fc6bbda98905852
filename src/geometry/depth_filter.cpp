#include "cropsight/geometry/depth_filter.hpp"

#include <cmath>
#include <limits>

#include "cropsight/core/error.hpp"

namespace cropsight::geometry {

void DepthRangeConfig::validate() const {
  if (!(min_depth >= 0.0f) || !std::isfinite(min_depth))
    throw Error("depth.min_depth", "must be a finite number >= 0 (metres)");
  if (!(max_depth > 0.0f) || !std::isfinite(max_depth))
    throw Error("depth.max_depth", "must be a finite positive number (metres)");
  if (!(min_depth <= max_depth)) throw Error("depth range", "min_depth must not exceed max_depth");
}

std::size_t filter_depth_range(OrganizedCloud& cloud, const DepthRangeConfig& cfg) {
  cfg.validate();
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  const bool normals = cloud.has_normals();
  std::size_t kept = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const float z = cloud.z[i];
    // The comparison is false for NaN, so NaN points are (re)written as NaN too.
    if (z >= cfg.min_depth && z <= cfg.max_depth) {
      ++kept;
      continue;
    }
    cloud.x[i] = cloud.y[i] = cloud.z[i] = kNaN;
    if (normals) cloud.nx[i] = cloud.ny[i] = cloud.nz[i] = cloud.curvature[i] = kNaN;
  }
  return kept;
}

std::vector<int> valid_indices(const OrganizedCloud& cloud) {
  std::vector<int> out;
  out.reserve(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (std::isfinite(cloud.z[i])) out.push_back(int(i));
  return out;
}

}  // namespace cropsight::geometry
