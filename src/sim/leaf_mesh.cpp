#include "leaf_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace cropsight::sim::detail {

Eigen::Vector3d midrib_tangent(const LeafShape& L, double s) {
  const double az = L.azimuth + L.yaw_bend * s;
  const double el = L.elevation0 + (L.elevation1 - L.elevation0) * std::pow(s, L.bend_power);
  return {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
}

double midrib_z_at_radius(const LeafShape& L, const Eigen::Vector2d& axis, double radius) {
  const int ns = std::max(3, L.segments);
  const double step = L.length / (ns - 1);
  Eigen::Vector3d p = L.start;
  double r_prev = (p.head<2>() - axis).norm();
  if (r_prev >= radius) return std::nan("");
  for (int i = 1; i < ns; ++i) {
    const Eigen::Vector3d q = p + midrib_tangent(L, double(i) / (ns - 1)) * step;
    const double r = (q.head<2>() - axis).norm();
    if (r >= radius) return p.z() + (q.z() - p.z()) * (radius - r_prev) / (r - r_prev);
    p = q;
    r_prev = r;
  }
  return std::nan("");
}

void add_leaf(Mesh& mesh, const LeafShape& L, SurfaceKind kind, Rng& rng) {
  const int ns = std::max(3, L.segments), nt = std::max(3, L.across | 1);
  const double step = L.length / (ns - 1);
  const double ruffle_freq = 3.0 + 4.0 * rng.uniform();  // waves along the margin
  const double ruffle_phase = 6.283185307 * rng.uniform();
  const double petiole_w = std::min(0.014, 0.12 * L.width);
  Eigen::Vector3d p = L.start;
  std::vector<std::uint32_t> idx(std::size_t(ns) * std::size_t(nt));
  for (int i = 0; i < ns; ++i) {
    const double s = double(i) / (ns - 1);
    const double az = L.azimuth + L.yaw_bend * s;
    const Eigen::Vector3d tangent = midrib_tangent(L, s);
    if (i > 0) p += tangent * step;
    // Blade axes: `side` horizontal and perpendicular to the leaf direction, rolled by the twist;
    // `nb` = tangent x side points up for a leaf that goes outward.
    Eigen::Vector3d side(-std::sin(az), std::cos(az), 0.0);
    const double roll = L.twist * s;
    const Eigen::Vector3d nb0 = tangent.cross(side).normalized();
    side = std::cos(roll) * side + std::sin(roll) * nb0;
    const Eigen::Vector3d nb = tangent.cross(side).normalized();
    double w;
    if (s < L.petiole) {
      w = petiole_w;
    } else {
      const double u = (s - L.petiole) / (1.0 - L.petiole);
      double profile = std::sin(3.141592653589793 * std::pow(u, L.blade_exponent));
      // Only a non-default fullness takes the power: the presets' leaves stay bit-identical.
      if (L.blade_fullness != 1.0) profile = std::pow(std::max(0.0, profile), L.blade_fullness);
      w = L.width * profile + petiole_w * (1.0 - u);
    }
    const bool blade = s >= L.petiole;
    for (int k = 0; k < nt; ++k) {
      const double t = -1.0 + 2.0 * k / (nt - 1);
      const double half = 0.5 * w;
      double lift = L.cup * half * t * t;
      if (blade) lift += L.ruffle * t * t * std::sin(6.283185307 * ruffle_freq * s + ruffle_phase + 3.0 * t);
      const Eigen::Vector3d q = p + side * (t * half) + nb * lift;
      Eigen::Vector3f c = L.color;
      const double rib = std::abs(t);
      if (!blade || rib < 0.15)
        c = 0.5f * (L.color + L.midrib_color);
      else
        c *= float(1.0 - 0.12 * rib);  // margins slightly darker (thinner wax layer)
      c *= float(rng.uniform(0.94, 1.06));
      idx[std::size_t(i) * nt + k] = mesh.add_vertex(q.cast<float>(), c, L.reflectivity);
    }
  }
  for (int i = 0; i + 1 < ns; ++i)
    for (int k = 0; k + 1 < nt; ++k) {
      const auto a = idx[std::size_t(i) * nt + k], b = idx[std::size_t(i + 1) * nt + k];
      const auto c = idx[std::size_t(i + 1) * nt + k + 1], d = idx[std::size_t(i) * nt + k + 1];
      mesh.add_triangle(a, b, c, 0, kind);
      mesh.add_triangle(a, c, d, 0, kind);
    }
}

}  // namespace cropsight::sim::detail
