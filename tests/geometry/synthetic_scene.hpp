#pragma once
// Test/bench input before the simulator: a synthetic organised cloud by ray casting through
// CameraIntrinsics::from_fov(w, h, 70.6°, 60°) (Kinect v2-like): a gently tilted, bumpy ground
// at ~0.85 m, a few spherical-cap "heads" (domes) rising from it, a tilted rectangular "leaf"
// floating above the ground, a few NaN holes, and deterministic depth noise.
// cloud.labels: 0 ground, 1..k dome k, 100 leaf (0 for NaN pixels).
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "cropsight/core/camera.hpp"
#include "cropsight/core/organized_cloud.hpp"

namespace cropsight::testing {

struct SyntheticSceneOptions {
  int width = 512;
  int height = 424;
  float noise_sigma = 0.0005f;  ///< m, Gaussian depth noise
  bool holes = true;
  unsigned seed = 7;
};

struct SyntheticScene {
  CameraIntrinsics camera;
  OrganizedCloud cloud;
  int domes = 0;
};

inline SyntheticScene make_synthetic_scene(const SyntheticSceneOptions& o = {}) {
  SyntheticScene s;
  s.camera = CameraIntrinsics::from_fov(o.width, o.height, 70.6 * M_PI / 180.0, 60.0 * M_PI / 180.0);
  const auto& cam = s.camera;
  s.cloud = OrganizedCloud(o.width, o.height);
  s.cloud.labels.assign(s.cloud.size(), 0);
  // Domes: centre (x, y) on the ground, sphere radius R, cap height above ground hgt.
  struct Dome {
    double x, y, r, hgt;
  };
  const std::vector<Dome> domes = {{-0.15, -0.10, 0.08, 0.07},
                                   {0.12, -0.12, 0.06, 0.05},
                                   {0.02, 0.12, 0.09, 0.06},
                                   {-0.22, 0.15, 0.05, 0.045},
                                   {0.25, 0.10, 0.07, 0.055}};
  s.domes = int(domes.size());
  std::mt19937 rng(o.seed);
  std::normal_distribution<float> noise(0.0f, o.noise_sigma);
  // Ground: plane z = 0.85 + 0.08 y + 0.03 x (camera frame), plus small bumps.
  auto ground_z = [](double x, double y) {
    return 0.85 + 0.08 * y + 0.03 * x + 0.004 * std::sin(x / 0.03) * std::cos(y / 0.05);
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int v = 0; v < o.height; ++v) {
    for (int u = 0; u < o.width; ++u) {
      const double rx = (u - cam.cx) / cam.fx, ry = (v - cam.cy) / cam.fy;
      // Ground: fixed-point iteration of z = ground_z(rx z, ry z) (contraction: slopes < 0.2).
      double zg = 0.85;
      for (int it = 0; it < 8; ++it) zg = ground_z(rx * zg, ry * zg);
      double best = zg;
      int label = 0;
      for (std::size_t k = 0; k < domes.size(); ++k) {
        const auto& d = domes[k];
        // Sphere centre below the cap top: centre depth = ground depth at (x, y) - hgt + r.
        const double cz = ground_z(d.x, d.y) - d.hgt + d.r;
        // Ray p = t·(rx, ry, 1): |t r - c|² = R².
        const double a = rx * rx + ry * ry + 1.0;
        const double b = -2.0 * (rx * d.x + ry * d.y + cz);
        const double c = d.x * d.x + d.y * d.y + cz * cz - d.r * d.r;
        const double disc = b * b - 4 * a * c;
        if (disc < 0) continue;
        const double t = (-b - std::sqrt(disc)) / (2 * a);
        if (t > 0 && t < best) {
          best = t;
          label = int(k) + 1;
        }
      }
      // Leaf: rectangle centred at (0.2, -0.02, 0.7), normal tilted, half-sizes 0.06 × 0.035 m.
      {
        const double lx = 0.20, ly = -0.02, lz = 0.70;
        const double nx = 0.35, ny = 0.2, nz = -0.915;  // roughly facing the camera
        const double den = nx * rx + ny * ry + nz;
        const double t = (nx * lx + ny * ly + nz * lz) / den;
        if (t > 0 && t < best) {
          const double px = rx * t - lx, py = ry * t - ly;
          if (std::abs(px) < 0.06 && std::abs(py) < 0.035) {
            best = t;
            label = 100;
          }
        }
      }
      double z = best + double(noise(rng));
      // Holes: a few discs in pixel space (no return).
      if (o.holes) {
        const double hu[3] = {0.3 * o.width, 0.62 * o.width, 0.8 * o.width};
        const double hv[3] = {0.7 * o.height, 0.35 * o.height, 0.8 * o.height};
        const double hr[3] = {0.02 * o.width, 0.015 * o.width, 0.03 * o.width};
        for (int k = 0; k < 3; ++k)
          if ((u - hu[k]) * (u - hu[k]) + (v - hv[k]) * (v - hv[k]) < hr[k] * hr[k]) z = nan;
      }
      if (!std::isfinite(z)) continue;
      const std::size_t i = std::size_t(v) * o.width + u;
      s.cloud.x[i] = float(rx * z);
      s.cloud.y[i] = float(ry * z);
      s.cloud.z[i] = float(z);
      s.cloud.labels[i] = std::uint16_t(label);
    }
  }
  return s;
}

}  // namespace cropsight::testing
