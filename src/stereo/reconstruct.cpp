#include "cropsight/stereo/reconstruct.hpp"

#include <cmath>

namespace cropsight::stereo {

StereoPoints reconstruct(const DisparityImage& d, const RectifiedGeometry& g, double min_depth, double max_depth) {
  StereoPoints out;
  out.points.reserve(d.size());
  out.pixels.reserve(d.size());
  const double fb = g.f * g.baseline, inv_f = 1.0 / g.f;
  // Disparity of the two principal points differs when cx_right != cx (not with zero-disparity
  // rectification, but calibrations from elsewhere may have it).
  const double doff = g.cx - g.cx_right;
  for (int v = 0; v < d.height; ++v) {
    const float* row = d.row(v);
    for (int u = 0; u < d.width; ++u) {
      const double disp = double(row[u]) - doff;
      if (!(disp > 0)) continue;  // NaN too
      const double z = fb / disp;
      if (z < min_depth || z > max_depth) continue;
      out.points.emplace_back(float((u - g.cx) * z * inv_f), float((v - g.cy) * z * inv_f), float(z));
      out.pixels.push_back(v * d.width + u);
    }
  }
  return out;
}

}  // namespace cropsight::stereo
