#include "seedling_render.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace cropsight::sim::seedling_detail {
namespace {

// Hash-based value noise: deterministic, cheap, band-limited enough for stereo matching when the
// finest octave is a few millimetres (about two pixels at 0.6 m).
inline float hash3(std::int64_t x, std::int64_t y, std::int64_t z, std::uint64_t seed) {
  std::uint64_t h = seed ^ (std::uint64_t(x) * 0x9E3779B97F4A7C15ull) ^ (std::uint64_t(y) * 0xC2B2AE3D27D4EB4Full) ^
                    (std::uint64_t(z) * 0x165667B19E3779F9ull);
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdull;
  h ^= h >> 33;
  h *= 0xc4ceb9fe1a85ec53ull;
  h ^= h >> 33;
  return float(h >> 40) * (1.0f / 16777216.0f);
}

inline float smooth(float t) { return t * t * (3 - 2 * t); }

float value_noise(const Eigen::Vector3f& q, std::uint64_t seed) {
  const float fx = std::floor(q.x()), fy = std::floor(q.y()), fz = std::floor(q.z());
  const auto ix = std::int64_t(fx), iy = std::int64_t(fy), iz = std::int64_t(fz);
  const float tx = smooth(q.x() - fx), ty = smooth(q.y() - fy), tz = smooth(q.z() - fz);
  float c[2][2][2];
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      for (int d = 0; d < 2; ++d) c[a][b][d] = hash3(ix + a, iy + b, iz + d, seed);
  auto lerp = [](float a, float b, float t) { return a + (b - a) * t; };
  const float x00 = lerp(c[0][0][0], c[1][0][0], tx), x10 = lerp(c[0][1][0], c[1][1][0], tx);
  const float x01 = lerp(c[0][0][1], c[1][0][1], tx), x11 = lerp(c[0][1][1], c[1][1][1], tx);
  return lerp(lerp(x00, x10, ty), lerp(x01, x11, ty), tz);
}

/// Fractal noise in [0, 1], finest wavelength `cell` metres.
float fbm(const Eigen::Vector3f& p, float cell, int octaves, std::uint64_t seed) {
  float sum = 0, amp = 0.5f, norm = 0;
  float scale = 1.0f / (cell * float(1 << (octaves - 1)));
  for (int o = 0; o < octaves; ++o) {
    sum += amp * value_noise(p * scale, seed + std::uint64_t(o) * 1013);
    norm += amp;
    amp *= 0.6f;
    scale *= 2.0f;
  }
  return sum / norm;
}

const Eigen::Vector3f kSun = Eigen::Vector3f(0.3f, -0.2f, 1.0f).normalized();

}  // namespace

void rasterize(const SMesh& mesh, const View& v, int factor, Samples& out) {
  const int w = v.width * factor, h = v.height * factor;
  out.w = w;
  out.h = h;
  out.depth.assign(std::size_t(w) * h, std::numeric_limits<float>::infinity());
  out.tri.assign(std::size_t(w) * h, -1);
  out.world.assign(std::size_t(w) * h, Eigen::Vector3f::Zero());
  out.uv.assign(std::size_t(w) * h, Eigen::Vector2f::Zero());
  const double f = v.f * factor;
  // Sub-sample (i, j) of pixel (u, v) sits at u + (i + 0.5) / factor - 0.5.
  const double cx = (v.cx + 0.5) * factor - 0.5, cy = (v.cy + 0.5) * factor - 0.5;
  const Eigen::Matrix3d R_wc = v.R_cw.transpose();

  // Soil plane z = 0, analytic per sample.
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const Eigen::Vector3d d_c((x - cx) / f, (y - cy) / f, 1.0);
      const Eigen::Vector3d d_w = v.R_cw * d_c;
      if (d_w.z() >= -1e-9) continue;
      const double t = -v.C.z() / d_w.z();  // camera z of the hit, since d_c.z = 1
      const std::size_t i = std::size_t(y) * w + x;
      out.depth[i] = float(t);
      out.world[i] = (v.C + t * d_w).cast<float>();
    }

  // Triangles: project, then fill with perspective-correct barycentrics.
  std::vector<Eigen::Vector3d> pc(mesh.p.size());
  for (std::size_t k = 0; k < mesh.p.size(); ++k) pc[k] = R_wc * (mesh.p[k].cast<double>() - v.C);
  for (std::size_t t = 0; t < mesh.tri.size(); ++t) {
    const auto& T = mesh.tri[t];
    const Eigen::Vector3d& a = pc[T[0]];
    const Eigen::Vector3d& b = pc[T[1]];
    const Eigen::Vector3d& c = pc[T[2]];
    if (a.z() < 0.05 || b.z() < 0.05 || c.z() < 0.05) continue;
    const Eigen::Vector2d pa(f * a.x() / a.z() + cx, f * a.y() / a.z() + cy);
    const Eigen::Vector2d pb(f * b.x() / b.z() + cx, f * b.y() / b.z() + cy);
    const Eigen::Vector2d pcc(f * c.x() / c.z() + cx, f * c.y() / c.z() + cy);
    const double area = (pb - pa).x() * (pcc - pa).y() - (pb - pa).y() * (pcc - pa).x();
    if (std::fabs(area) < 1e-12) continue;
    const int x0 = std::max(0, int(std::ceil(std::min({pa.x(), pb.x(), pcc.x()}))));
    const int x1 = std::min(w - 1, int(std::floor(std::max({pa.x(), pb.x(), pcc.x()}))));
    const int y0 = std::max(0, int(std::ceil(std::min({pa.y(), pb.y(), pcc.y()}))));
    const int y1 = std::min(h - 1, int(std::floor(std::max({pa.y(), pb.y(), pcc.y()}))));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const Eigen::Vector2d q(x, y);
        const double l0 = ((pb - q).x() * (pcc - q).y() - (pb - q).y() * (pcc - q).x()) / area;
        const double l1 = ((pcc - q).x() * (pa - q).y() - (pcc - q).y() * (pa - q).x()) / area;
        const double l2 = 1.0 - l0 - l1;
        if (l0 < 0 || l1 < 0 || l2 < 0) continue;
        const double w0 = l0 / a.z(), w1 = l1 / b.z(), w2 = l2 / c.z();
        const double z = 1.0 / (w0 + w1 + w2);
        const std::size_t i = std::size_t(y) * w + x;
        if (z >= out.depth[i]) continue;
        out.depth[i] = float(z);
        out.tri[i] = int(t);
        const double g0 = w0 * z, g1 = w1 * z, g2 = w2 * z;
        out.world[i] =
            (g0 * mesh.p[T[0]].cast<double>() + g1 * mesh.p[T[1]].cast<double>() + g2 * mesh.p[T[2]].cast<double>())
                .cast<float>();
        out.uv[i] =
            (g0 * mesh.uv[T[0]].cast<double>() + g1 * mesh.uv[T[1]].cast<double>() + g2 * mesh.uv[T[2]].cast<double>())
                .cast<float>();
      }
  }
}

Eigen::Vector3f sample_color(const SMesh& mesh, const Samples& s, int i, std::uint64_t seed) {
  const Eigen::Vector3f& p = s.world[std::size_t(i)];
  const int t = s.tri[std::size_t(i)];
  if (!std::isfinite(s.depth[std::size_t(i)])) return {0, 0, 0};
  if (t < 0) {
    // Soil: brown, clods at ~2 cm, grain at ~3 mm, sparse light pebbles.
    const float coarse = fbm(p, 0.02f, 2, seed + 11);
    const float fine = fbm(p, 0.003f, 3, seed + 23);
    const float pebble = value_noise(p * 180.0f, seed + 37) > 0.88f ? 1.5f : 1.0f;
    const float k = (0.55f + 0.5f * coarse + 0.6f * (fine - 0.5f)) * pebble;
    return Eigen::Vector3f(118, 92, 66) * k;
  }
  const auto& T = mesh.tri[std::size_t(t)];
  const Eigen::Vector3f n = (mesh.p[T[1]] - mesh.p[T[0]]).cross(mesh.p[T[2]] - mesh.p[T[0]]).normalized();
  const float shade = 0.45f + 0.55f * std::fabs(n.dot(kSun));
  const Eigen::Vector2f& st = s.uv[std::size_t(i)];
  float k = 0.75f + 0.5f * fbm(p, 0.004f, 3, seed + 51 + mesh.mat[std::size_t(t)]);
  if (mesh.mat[std::size_t(t)] == kLeaf || mesh.mat[std::size_t(t)] == kWeed) {
    // Midrib and lateral veins: lighter lines that give leaves matchable structure.
    const float mid = std::fabs(st.y());
    if (mid < 0.06f) k *= 1.25f;
    const float lateral = std::fabs(std::fmod(st.x() * 7.0f - mid * 1.5f + 10.0f, 1.0f) - 0.5f);
    if (lateral < 0.06f && mid < 0.85f) k *= 1.15f;
  }
  return mesh.base_color[std::size_t(t)] * (k * shade);
}

}  // namespace cropsight::sim::seedling_detail
