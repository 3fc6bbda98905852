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

// The potato's silhouette in the box: pixels whose depth lies in [z - near, z + depth_band]
// (a root in front and the backdrop behind drop out; the rim of a potato lies less than half its
// length behind its front).
// Its size is measured as seen looking straight along the ray `c` to the box centre: each pixel's
// ray is cut by the plane at unit distance perpendicular to c (basis e1, e2). Plain image
// coordinates would stretch an off-axis potato radially by 1 / cos(angle off axis), 15 % at 30 deg.
// Second moments of a filled ellipse: variance along a semi-axis s is s^2 / 4.
struct Silhouette {
  int pixels = 0;
  double minor = 0, major = 0;  ///< full axes of the equivalent ellipse, radians (metres per metre along c)
  Eigen::Vector3d centroid_ray = Eigen::Vector3d::UnitZ();  ///< unit ray through the silhouette's centroid
};

Silhouette silhouette(const Detection2D& box, const Image<float>& depth_m, const CameraIntrinsics& camera,
                      const Eigen::Vector3d& c, float z, float near_m, float band_m) {
  const Eigen::Vector3d e1 = (Eigen::Vector3d::UnitX() - c.x() * c).normalized(), e2 = c.cross(e1);
  const int u0 = std::clamp(int(std::floor(box.x1)), 0, depth_m.width);
  const int u1 = std::clamp(int(std::ceil(box.x2)), 0, depth_m.width);
  const int v0 = std::clamp(int(std::floor(box.y1)), 0, depth_m.height);
  const int v1 = std::clamp(int(std::ceil(box.y2)), 0, depth_m.height);
  const float lo = z - near_m, hi = z + band_m;
  double n = 0, sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
  for (int v = v0; v < v1; ++v) {
    const float* row = depth_m.row(v);
    const double yn = (double(v) - camera.cy) / camera.fy;
    for (int u = u0; u < u1; ++u) {
      if (!(row[u] >= lo && row[u] <= hi)) continue;
      const Eigen::Vector3d d((double(u) - camera.cx) / camera.fx, yn, 1.0);
      const double t = 1.0 / d.dot(c), a = t * d.dot(e1), b = t * d.dot(e2);
      n += 1, sa += a, sb += b, saa += a * a, sbb += b * b, sab += a * b;
    }
  }
  Silhouette s;
  s.pixels = int(n);
  if (n < 3) return s;
  const double ma = sa / n, mb = sb / n;
  const double caa = saa / n - ma * ma, cbb = sbb / n - mb * mb, cab = sab / n - ma * mb;
  const double mean = 0.5 * (caa + cbb), d = std::sqrt(0.25 * (caa - cbb) * (caa - cbb) + cab * cab);
  s.centroid_ray = (c + ma * e1 + mb * e2).normalized();
  s.minor = 4.0 * std::sqrt(std::max(0.0, mean - d));
  s.major = 4.0 * std::sqrt(std::max(0.0, mean + d));
  return s;
}
}  // namespace

Position3D locate(const Detection2D& box, const Image<float>& depth_m, const CameraIntrinsics& camera,
                  const PositionConfig& cfg) {
  Position3D out;
  if (depth_m.empty() || box.area() <= 0) return out;
  out.cut_by_border =
      box.x1 < 1.f || box.y1 < 1.f || box.x2 > float(depth_m.width) - 1.f || box.y2 > float(depth_m.height) - 1.f;
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

  // The centre lies one semi-axis behind the surface point along the ray c through the box centre.
  // The semi-axis is an angle `semi` (metres = semi * distance) seen at the centre's distance (the
  // silhouette lies near the centre, not the surface): rho_c = rho_s + semi * rho_c.
  const Eigen::Vector3d ray((double(cu) - 0.5 - camera.cx) / camera.fx, (double(cv) - 0.5 - camera.cy) / camera.fy,
                            1.0);
  Eigen::Vector3d c = ray.normalized();
  const double rho_s = double(z) * ray.norm();
  double semi = 0;
  CentreOffset offset = cfg.centre_offset;
  if (offset == CentreOffset::silhouette) {
    const float band = 0.5f * float(std::max(box.width() / camera.fx, box.height() / camera.fy)) * z;
    const Silhouette s = silhouette(box, depth_m, camera, c, z, float(cfg.silhouette_near_m), band);
    out.silhouette_pixels = s.pixels;
    if (s.pixels >= cfg.silhouette_min_px) {
      semi = 0.5 * s.minor;
      const double rho_c = rho_s / std::max(0.5, 1.0 - semi);
      out.minor_m = float(s.minor * rho_c);
      out.major_m = float(s.major * rho_c);
      // The centre's ray: through the silhouette's centroid, which sprouts and a box cut a little
      // wide or narrow by the detector move less than they move the box centre.
      if (cfg.ray == CentreRay::silhouette) c = s.centroid_ray;
    } else {
      offset = CentreOffset::half_width;
    }
  }
  if (offset == CentreOffset::half_width) semi = 0.5 * std::min(box.width() / camera.fx, box.height() / camera.fy);
  const double rho_c = rho_s / std::max(0.5, 1.0 - semi);
  out.xyz = (rho_c * c).cast<float>();
  const float zc = out.xyz.z();
  const float w = float(box.width() * zc / camera.fx), h = float(box.height() * zc / camera.fy);
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
