#pragma once
// Smooth 2D value noise on an integer lattice, hashed from the seed (no tables, no state), and
// its fractal sum. Used for soil relief and colour patches: a pure function of (seed, x, y), so
// adjacent soil tiles agree exactly on their shared edge.
#include <cmath>
#include <cstdint>

#include "cropsight/sim/random.hpp"

namespace cropsight::sim::detail {

inline double lattice_value(std::uint64_t seed, std::int64_t ix, std::int64_t iy) {
  std::uint64_t s = seed ^ (std::uint64_t(ix) * 0x9E3779B97F4A7C15ull) ^ (std::uint64_t(iy) * 0xC2B2AE3D27D4EB4Full);
  return double(splitmix64(s) >> 11) * 0x1.0p-52 - 1.0;  // [-1, 1)
}

/// Value noise in [-1, 1] with quintic (C2) interpolation; lattice spacing 1.
inline double value_noise(std::uint64_t seed, double x, double y) {
  const double fx = std::floor(x), fy = std::floor(y);
  const auto ix = std::int64_t(fx), iy = std::int64_t(fy);
  const double tx = x - fx, ty = y - fy;
  const double sx = tx * tx * tx * (tx * (tx * 6 - 15) + 10);
  const double sy = ty * ty * ty * (ty * (ty * 6 - 15) + 10);
  const double v00 = lattice_value(seed, ix, iy), v10 = lattice_value(seed, ix + 1, iy);
  const double v01 = lattice_value(seed, ix, iy + 1), v11 = lattice_value(seed, ix + 1, iy + 1);
  const double a = v00 + (v10 - v00) * sx, b = v01 + (v11 - v01) * sx;
  return a + (b - a) * sy;
}

/// Fractal sum of `octaves` octaves (each half the scale and amplitude), roughly in [-1, 1].
inline double fbm(std::uint64_t seed, double x, double y, int octaves) {
  double sum = 0, amp = 0.5, norm = 0, f = 1;
  for (int o = 0; o < octaves; ++o) {
    sum += amp * value_noise(seed + std::uint64_t(o) * 0x632BE59BD9B4E019ull, x * f, y * f);
    norm += amp;
    amp *= 0.5;
    f *= 2.0;
  }
  return sum / norm;
}

}  // namespace cropsight::sim::detail
