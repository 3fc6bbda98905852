#include "cropsight/features/viewpoint_angle.hpp"

#include <algorithm>
#include <cmath>

namespace cropsight::features {

void compute_viewpoint_angle_histogram(const OrganizedCloud& cloud, std::span<const int> indices, float* out) {
  std::fill(out, out + kViewpointAngleBins, 0.0f);
  if (!cloud.has_normals()) return;
  constexpr float kBinsPerRad = float(kViewpointAngleBins) / float(M_PI / 2.0);
  int n = 0;
  for (int i : indices) {
    const float px = cloud.x[i], py = cloud.y[i], pz = cloud.z[i];
    const float nx = cloud.nx[i], ny = cloud.ny[i], nz = cloud.nz[i];
    if (!(std::isfinite(pz) && std::isfinite(nx) && std::isfinite(ny) && std::isfinite(nz))) continue;
    const float len = std::sqrt(px * px + py * py + pz * pz);
    if (!(len > 0.0f)) continue;
    // cos θ = n · (0 - p)/|p|
    const float c = std::clamp(-(nx * px + ny * py + nz * pz) / len, -1.0f, 1.0f);
    const float theta = std::acos(c);
    const int bin = std::clamp(int(theta * kBinsPerRad), 0, kViewpointAngleBins - 1);
    out[bin] += 1.0f;
    ++n;
  }
  if (n > 0)
    for (int b = 0; b < kViewpointAngleBins; ++b) out[b] /= float(n);
}

}  // namespace cropsight::features
