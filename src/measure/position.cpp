// Box-centre deprojection with a robust depth (see position.hpp).
#include "cropsight/measure/position.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "cropsight/core/error.hpp"
#include "cropsight/measure/depth_flood.hpp"

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
  // The equivalent ellipse in the plane at unit distance along c: centroid (ma, mb), covariance.
  Eigen::Vector3d e1 = Eigen::Vector3d::UnitX(), e2 = Eigen::Vector3d::UnitY();
  double ma = 0, mb = 0, caa = 0, cbb = 0, cab = 0;
};

// The silhouette's pixels: those of the box whose depth lies in [lo, hi], and with grow > 0 those
// up to `grow` of the box's sides beyond it that are connected to them (8-neighbours, in the band,
// depth steps up to `step`): a detector's box that cuts off a dark end of the potato no longer cuts
// its silhouette. Inside the box nothing needs a connection: a root across the potato removes a
// strip from the band and would cut the silhouette in two. Thread-safety: the mask reuses a
// thread_local buffer.
struct SilhouetteMask {
  int u0 = 0, v0 = 0, width = 0, height = 0;
  const std::vector<std::uint8_t>* in = nullptr;  ///< row-major, width x height, 1 = silhouette
  bool at(int u, int v) const { return (*in)[std::size_t(v - v0) * std::size_t(width) + std::size_t(u - u0)] != 0; }
};

SilhouetteMask silhouette_mask(const Detection2D& box, const Image<float>& depth_m, float lo, float hi, double grow,
                               float step, int opening_px) {
  const double gw = grow * box.width(), gh = grow * box.height();
  SilhouetteMask m;
  m.u0 = std::clamp(int(std::floor(box.x1 - gw)), 0, depth_m.width);
  m.v0 = std::clamp(int(std::floor(box.y1 - gh)), 0, depth_m.height);
  const int u1 = std::clamp(int(std::ceil(box.x2 + gw)), 0, depth_m.width);
  const int v1 = std::clamp(int(std::ceil(box.y2 + gh)), 0, depth_m.height);
  m.width = std::max(0, u1 - m.u0), m.height = std::max(0, v1 - m.v0);
  thread_local std::vector<std::uint8_t> in;
  in.assign(std::size_t(m.width) * std::size_t(m.height), 0);
  m.in = &in;
  const auto band = [&](int u, int v) {
    const float d = depth_m.at(u, v);
    return d >= lo && d <= hi;
  };
  if (grow <= 0) {
    for (int v = m.v0; v < v1; ++v)
      for (int u = m.u0; u < u1; ++u)
        in[std::size_t(v - m.v0) * std::size_t(m.width) + std::size_t(u - m.u0)] = band(u, v);
    return m;
  }
  thread_local std::vector<std::pair<int, int>> stack;
  stack.clear();
  const auto mark = [&](int u, int v) {
    std::uint8_t& f = in[std::size_t(v - m.v0) * std::size_t(m.width) + std::size_t(u - m.u0)];
    if (f != 0) return false;
    f = 1;
    return true;
  };
  const int bu0 = std::clamp(int(std::floor(box.x1)), 0, depth_m.width);
  const int bu1 = std::clamp(int(std::ceil(box.x2)), 0, depth_m.width);
  const int bv0 = std::clamp(int(std::floor(box.y1)), 0, depth_m.height);
  const int bv1 = std::clamp(int(std::ceil(box.y2)), 0, depth_m.height);
  // Inside the box every in-band pixel counts; only those on its edge can reach beyond it.
  for (int v = bv0; v < bv1; ++v)
    for (int u = bu0; u < bu1; ++u) {
      if (!band(u, v)) continue;
      in[std::size_t(v - m.v0) * std::size_t(m.width) + std::size_t(u - m.u0)] = 1;
      if (u == bu0 || v == bv0 || u == bu1 - 1 || v == bv1 - 1) stack.emplace_back(u, v);
    }
  const auto inside_box = [&](int u, int v) { return u >= bu0 && v >= bv0 && u < bu1 && v < bv1; };
  flood_depth(
      depth_m, m.u0, m.v0, u1, v1, step, stack, [&](int u, int v) { return !inside_box(u, v) && band(u, v); }, mark);
  // Strings, roots and sprouts at the potato's depth are a few pixels wide: an opening removes
  // them, so that they neither widen the equivalent ellipse nor bend the profile fit.
  if (opening_px >= 2 && m.width > 0 && m.height > 0) {
    cv::Mat view(m.height, m.width, CV_8UC1, in.data());
    cv::morphologyEx(view, view, cv::MORPH_OPEN,
                     cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(opening_px, opening_px)));
  }
  return m;
}

// Moments of the mask's pixels, each measured across the ray c (see Silhouette).
Silhouette silhouette(const SilhouetteMask& mask, const CameraIntrinsics& camera, const Eigen::Vector3d& c) {
  const Eigen::Vector3d e1 = (Eigen::Vector3d::UnitX() - c.x() * c).normalized(), e2 = c.cross(e1);
  double n = 0, sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
  for (int v = mask.v0; v < mask.v0 + mask.height; ++v) {
    const double yn = (double(v) - camera.cy) / camera.fy;
    for (int u = mask.u0; u < mask.u0 + mask.width; ++u) {
      if (!mask.at(u, v)) continue;
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
  s.e1 = e1, s.e2 = e2, s.ma = ma, s.mb = mb, s.caa = caa, s.cbb = cbb, s.cab = cab;
  s.minor = 4.0 * std::sqrt(std::max(0.0, mean - d));
  s.major = 4.0 * std::sqrt(std::max(0.0, mean + d));
  return s;
}
// The centre's distance along the silhouette's centroid ray from the shape of the visible surface
// (centre_offset: profile). An ellipsoid at distance D whose semi-axis along the view is C: a pixel
// at normalised radius rho inside the silhouette's equivalent ellipse (offset (da, db) from its
// centroid in the plane at unit distance) sees its front at range
//   r = D + g1 da + g2 db - C sqrt(1 - rho^2) + D (da^2 + db^2) / 2 - rho^2 C^2 / D
// to second order in the angles (exact for a sphere: r = D cos(phi) - sqrt(R^2 - D^2 sin^2 phi)).
// g1, g2: the rim's plane is tilted when the potato is. C is the thickness the silhouette cannot
// show. The last two terms (about a millimetre) are taken at the previous estimate, so the model
// is linear in (D, g1, g2, C): least squares over the pixels with rho below max_radius (the rim's
// depth is noisy and often missing), again without the residuals beyond three robust sigmas (a
// root or sprout on the surface), and once more with the terms at the new estimate. `d0`, `c0`:
// the first estimate. Returns {D, C}, or {0, 0} when too few pixels remain.
std::pair<double, double> fit_profile(const SilhouetteMask& mask, const Image<float>& depth_m,
                                      const CameraIntrinsics& camera, const Silhouette& s, double d0, double c0,
                                      double max_radius, int min_pixels) {
  // Inverse of 4 x covariance: for a filled ellipse of semi-axes p, q the covariance is diag(p^2, q^2) / 4.
  const double det = s.caa * s.cbb - s.cab * s.cab;
  if (!(det > 0) || !(d0 > 0)) return {0, 0};
  const double iaa = s.cbb / (4 * det), ibb = s.caa / (4 * det), iab = -s.cab / (4 * det);
  const Eigen::Vector3d c = s.e1.cross(s.e2);
  struct Row {
    Eigen::Vector4d x;  ///< 1, da, db, -sqrt(1 - rho^2)
    double r, lateral2, rho2;
  };
  thread_local std::vector<Row> rows;
  rows.clear();
  for (int v = mask.v0; v < mask.v0 + mask.height; ++v) {
    const float* row = depth_m.row(v);
    const double yn = (double(v) - camera.cy) / camera.fy;
    for (int u = mask.u0; u < mask.u0 + mask.width; ++u) {
      if (!mask.at(u, v)) continue;
      const Eigen::Vector3d d((double(u) - camera.cx) / camera.fx, yn, 1.0);
      const double t = 1.0 / d.dot(c), da = t * d.dot(s.e1) - s.ma, db = t * d.dot(s.e2) - s.mb;
      const double rho2 = iaa * da * da + 2 * iab * da * db + ibb * db * db;
      if (rho2 >= max_radius * max_radius) continue;
      rows.push_back(
          {Eigen::Vector4d(1.0, da, db, -std::sqrt(1.0 - rho2)), double(row[u]) * d.norm(), da * da + db * db, rho2});
    }
  }
  // Pass 0 fits every pixel with the terms at the first estimate; its residuals set the outlier
  // cutoff; passes 1 and 2 fit the inliers of the previous fit with the terms at its estimate.
  double dist = d0, thick = c0;
  Eigen::Vector4d beta = Eigen::Vector4d::Zero();
  double cutoff = std::numeric_limits<double>::infinity();
  thread_local std::vector<double> abs_res;
  for (int pass = 0; pass < 3; ++pass) {
    const Eigen::Vector4d previous = beta;
    const auto target = [&](const Row& q) { return q.r - 0.5 * dist * q.lateral2 + q.rho2 * thick * thick / dist; };
    Eigen::Matrix4d ata = Eigen::Matrix4d::Zero();
    Eigen::Vector4d atb = Eigen::Vector4d::Zero();
    int used = 0;
    for (const Row& q : rows) {
      const double y = target(q);
      if (pass > 0 && std::abs(q.x.dot(previous) - y) > cutoff) continue;
      ata.noalias() += q.x * q.x.transpose();
      atb.noalias() += q.x * y;
      ++used;
    }
    if (used < min_pixels) return {0, 0};
    const Eigen::LDLT<Eigen::Matrix4d> ldlt(ata);
    if (ldlt.info() != Eigen::Success) return {0, 0};
    beta = ldlt.solve(atb);
    if (pass == 0) {
      abs_res.clear();
      for (const Row& q : rows) abs_res.push_back(std::abs(q.x.dot(beta) - target(q)));
      auto mid = abs_res.begin() + std::ptrdiff_t(abs_res.size() / 2);
      std::nth_element(abs_res.begin(), mid, abs_res.end());
      cutoff = std::max(3.0 * 1.4826 * *mid, 1e-4);  // floor 0.1 mm: the depth's units are 1 mm
    }
    if (!(beta(0) > 0)) return {0, 0};
    dist = beta(0), thick = beta(3);
  }
  return {dist, thick};
}
}  // namespace

// Long on purpose: the depth at the box (centre or window), the surface point, the thickness and the centre, in order.
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
  if (offset == CentreOffset::silhouette || offset == CentreOffset::profile) {
    const float band = 0.5f * float(std::max(box.width() / camera.fx, box.height() / camera.fy)) * z;
    const float near = float(cfg.silhouette_near_m);
    const SilhouetteMask mask = silhouette_mask(box, depth_m, z - near, z + band, cfg.silhouette_grow,
                                                float(cfg.silhouette_step_m), cfg.silhouette_opening_px);
    const Silhouette s = silhouette(mask, camera, c);
    out.silhouette_pixels = s.pixels;
    if (offset == CentreOffset::profile && s.pixels >= cfg.silhouette_min_px) {
      // The fitted thickness must be a potato's: within profile_max_ratio of the silhouette's
      // semi-minor axis at the fitted distance; otherwise (a box on two potatoes, a flat patch of
      // backdrop) the round cross-section of `silhouette` is the safer guess.
      const double semi0 = 0.5 * s.minor, dist0 = rho_s / std::max(0.5, 1.0 - semi0);
      const auto [dist, thick] =
          fit_profile(mask, depth_m, camera, s, dist0, semi0 * dist0, cfg.profile_max_radius, cfg.silhouette_min_px);
      const double semi_m = 0.5 * s.minor * dist;
      if (dist > 0 && thick * cfg.profile_max_ratio >= semi_m && thick <= cfg.profile_max_ratio * semi_m) {
        out.xyz = (dist * s.centroid_ray).cast<float>();
        out.thickness_m = float(2 * thick);
        out.minor_m = float(s.minor * dist);
        out.major_m = float(s.major * dist);
        const float zc = out.xyz.z();
        out.width_m = float(box.width() * zc / camera.fx);
        out.height_m = float(box.height() * zc / camera.fy);
        out.area_m2 = out.width_m * out.height_m;
        return out;
      }
      offset = CentreOffset::silhouette;
    }
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
