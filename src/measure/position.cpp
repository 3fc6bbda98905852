// Box-centre deprojection with a robust depth (see position.hpp).
#include "cropsight/measure/position.hpp"

#include <algorithm>
#include <cmath>

#include "cropsight/core/error.hpp"

namespace cropsight::measure {

void PositionConfig::validate(const std::string& where) const {
  check_config(*this, where);
  if (!(max_depth_m > min_depth_m)) throw Error(where, "max_depth_m must be greater than min_depth_m");
}

namespace {
// Pixel index range [lo, hi) of a window of `side` pixels centred on continuous coordinate c,
// clipped to [0, n).
std::pair<int, int> window_range(float c, int side, int n) {
  const int lo = int(std::floor(c - 0.5f * float(side) + 0.5f));
  return {std::clamp(lo, 0, n), std::clamp(lo + side, 0, n)};
}
}  // namespace

Position3D locate(const Detection2D& box, const Image<float>& depth_m, const CameraIntrinsics& camera,
                  const PositionConfig& cfg) {
  Position3D out;
  if (depth_m.empty() || box.area() <= 0) return out;
  // Continuous box centre; pixel (u, v) spans [u, u+1), so its centre is at u + 0.5 in box
  // coordinates and at u in the intrinsics' convention (pixel centres at integers).
  const float cu = box.centre_x(), cv = box.centre_y();
  float z = 0;
  if (cfg.sampling == DepthSampling::centre_pixel) {
    const int u = int(std::floor(cu)), v = int(std::floor(cv));
    out.window_pixels = 1;
    if (u >= 0 && v >= 0 && u < depth_m.width && v < depth_m.height && depth_m.at(u, v) > 0) {
      z = depth_m.at(u, v);
      out.valid_pixels = 1;
    }
  } else {
    const int sw = std::max(cfg.window_min_px, int(std::lround(cfg.window_fraction * box.width())));
    const int sh = std::max(cfg.window_min_px, int(std::lround(cfg.window_fraction * box.height())));
    const auto [u0, u1] = window_range(cu, sw, depth_m.width);
    const auto [v0, v1] = window_range(cv, sh, depth_m.height);
    thread_local std::vector<float> values;
    values.clear();
    for (int v = v0; v < v1; ++v) {
      const float* row = depth_m.row(v);
      for (int u = u0; u < u1; ++u)
        if (row[u] > 0) values.push_back(row[u]);
    }
    out.window_pixels = sw * sh;
    out.valid_pixels = int(values.size());
    if (!values.empty()) {
      // Upper median: exact for odd counts, and no averaging of two surfaces (potato / root) for even ones.
      auto mid = values.begin() + std::ptrdiff_t(values.size() / 2);
      std::nth_element(values.begin(), mid, values.end());
      z = *mid;
    }
  }
  out.surface_depth_m = z;
  const bool enough = out.valid_pixels > 0 && double(out.valid_pixels) >= cfg.min_valid_fraction * out.window_pixels;
  if (!enough || z <= 0) return out;
  out.depth_ok = z >= cfg.min_depth_m && z <= cfg.max_depth_m;

  // Metric box sides at the surface depth first; the centre lies half a width behind it.
  float w = float(box.width() * z / camera.fx), h = float(box.height() * z / camera.fy);
  float zc = z;
  if (cfg.centre_offset == CentreOffset::half_width) {
    // The silhouette (what the box spans) lies near the centre's depth, not the surface's:
    // solve zc = z + 0.5 * min(w, h) * zc / z, i.e. zc = z / (1 - 0.5 * min side in pixels / f).
    const double k = 0.5 * std::min(box.width() / camera.fx, box.height() / camera.fy);
    zc = float(z / std::max(0.5, 1.0 - k));
    w = float(box.width() * zc / camera.fx);
    h = float(box.height() * zc / camera.fy);
  }
  // Move along the ray through the box centre so that the point's z is zc.
  out.xyz = camera.deproject(cu - 0.5f, cv - 0.5f, zc);
  out.width_m = w;
  out.height_m = h;
  out.area_m2 = w * h;
  return out;
}

Image<float> depth_in_metres(const DepthImage& depth, double depth_scale) {
  Image<float> out(depth.width, depth.height, 0.f);
  for (std::size_t i = 0; i < depth.data.size(); ++i) out.data[i] = float(depth.data[i] * depth_scale);
  return out;
}

}  // namespace cropsight::measure
