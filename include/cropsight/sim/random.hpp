#pragma once
// Portable, hand-written random numbers for the simulators.
//
// Why not <random> distributions: std::normal_distribution & co. are implementation-defined,
// so the same seed would give different scenes with another standard library. Everything here
// is specified bit for bit (xoshiro256** seeded through SplitMix64, Box-Muller normals), so a
// seed names the same field on every platform. The generator is cheap to seed, which lets the
// sensor model give every pixel of every frame its own stream (derive_seed(seed, frame, pixel))
// and stay deterministic when pixels are processed in parallel.
#include <cmath>
#include <cstdint>
#include <initializer_list>

namespace cropsight::sim {

/// SplitMix64 step (Steele et al. 2014): a strong 64-bit mixer, used for seeding and hashing.
inline std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

/// Combines a seed with any number of integer tags into a new, well-mixed seed.
inline std::uint64_t derive_seed(std::uint64_t seed, std::initializer_list<std::int64_t> tags) {
  std::uint64_t s = seed ^ 0x5DEECE66Dull;
  std::uint64_t h = splitmix64(s);
  for (std::int64_t t : tags) {
    s = h ^ (std::uint64_t(t) * 0xD6E8FEB86659FD93ull);
    h = splitmix64(s);
  }
  return h;
}

/// xoshiro256** (Blackman & Vigna 2018) with fixed, portable distributions.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) {
    std::uint64_t s = seed;
    for (auto& w : s_) w = splitmix64(s);
  }

  std::uint64_t next() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }

  /// Uniform in [0, 1), 53 random bits.
  double uniform() { return double(next() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// Uniform integer in [lo, hi] (inclusive); lo <= hi.
  int uniform_int(int lo, int hi) { return lo + int(uniform() * double(hi - lo + 1)); }
  bool bernoulli(double p) { return uniform() < p; }

  /// Standard normal by the Box-Muller transform (both values used).
  double normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u1 = uniform();
    while (u1 <= 0.0) u1 = uniform();
    const double u2 = uniform();
    const double r = std::sqrt(-2.0 * std::log(u1));
    const double a = 6.283185307179586 * u2;
    spare_ = r * std::sin(a);
    has_spare_ = true;
    return r * std::cos(a);
  }
  double normal(double mean, double sigma) { return mean + sigma * normal(); }

  /// Poisson count (Knuth's product method; fine for the small means used here, < ~50).
  int poisson(double mean) {
    if (mean <= 0) return 0;
    const double limit = std::exp(-mean);
    double p = uniform();
    int k = 0;
    while (p > limit) {
      p *= uniform();
      ++k;
    }
    return k;
  }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t s_[4];
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace cropsight::sim
