#pragma once
// Internal: float vectors (GCC/Clang vector extensions, lowered to whatever SIMD the
// target has) with Cephes-style exp and log, for the GMM / k-means hot loops. Accuracy of
// vexp / vlog: about 2 ulp over the ranges used (exp of values <= 0, log of values >= 1).
// __builtin_bit_cast, not std::bit_cast: the std template is compiled for the baseline, and
// returning an AVX vector from it changes the ABI inside the AVX2 variant (-Wpsabi).
#include <cstdint>

namespace cropsight::segmentation::simd {

// 8 lanes where AVX is enabled (-march=native builds, or a CROPSIGHT_AVX2_FMA_BEGIN region of
// core/cpu_dispatch.hpp that defines CROPSIGHT_SIMD_LANES 8 first), else 4 (SSE2, the x86-64 baseline): wider
// vectors without AVX would only be split again. Everything here has internal linkage (anonymous
// namespace), so a translation unit compiled for AVX2 and one for SSE2 can both include this
// header without the linker merging one's helpers into the other (an AVX2 instruction reached
// on a CPU without it would be SIGILL).
#ifndef CROPSIGHT_SIMD_LANES
#ifdef __AVX__
#define CROPSIGHT_SIMD_LANES 8
#else
#define CROPSIGHT_SIMD_LANES 4
#endif
#endif
namespace {
constexpr int kLanes = CROPSIGHT_SIMD_LANES;
using vf = float __attribute__((vector_size(4 * kLanes)));
using vi = std::int32_t __attribute__((vector_size(4 * kLanes)));

inline vf splat(float x) { return vf{} + x; }
inline vf vmax(vf a, vf b) { return a > b ? a : b; }
inline vf vmin(vf a, vf b) { return a < b ? a : b; }
inline float hsum(vf a) {
  float s = 0;
  for (int i = 0; i < kLanes; ++i) s += a[i];
  return s;
}
inline double hsum_d(vf a) {
  double s = 0;
  for (int i = 0; i < kLanes; ++i) s += double(a[i]);
  return s;
}

/// e^x, x clamped to [-87, 88].
inline vf vexp(vf x) {
  x = vmin(vmax(x, splat(-87.0f)), splat(88.0f));
  vf fx = x * 1.44269504088896341f + 0.5f;
  vi n = __builtin_convertvector(fx, vi);  // truncation toward zero
  vf fn = __builtin_convertvector(n, vf);
  fn = fn > fx ? fn - 1.0f : fn;  // floor
  n = __builtin_convertvector(fn, vi);
  x = x - fn * 0.693359375f - fn * -2.12194440e-4f;
  vf z = x * x;
  vf y = ((((1.9875691500e-4f * x + 1.3981999507e-3f) * x + 8.3334519073e-3f) * x + 4.1665795894e-2f) * x +
          1.6666665459e-1f) *
             x +
         5.0000001201e-1f;
  y = y * z + x + 1.0f;
  vi e = (n + 127) << 23;
  return y * __builtin_bit_cast(vf, e);
}

/// Natural logarithm of positive normal floats.
inline vf vlog(vf x) {
  vi xi = __builtin_bit_cast(vi, x);
  vi e = ((xi >> 23) & 0xff) - 127;
  vi mi = (xi & 0x007fffff) | 0x3f800000;
  vf m = __builtin_bit_cast(vf, mi);  // [1, 2)
  vi big = m > 1.41421356f;
  m = big ? m * 0.5f : m;
  e = e - big;  // big is -1 where true
  vf fe = __builtin_convertvector(e, vf);
  vf t = m - 1.0f;
  vf z = t * t;
  vf y = ((((((((7.0376836292e-2f * t - 1.1514610310e-1f) * t + 1.1676998740e-1f) * t - 1.2420140846e-1f) * t +
              1.4249322787e-1f) *
                 t -
             1.6668057665e-1f) *
                t +
            2.0000714765e-1f) *
               t -
           2.4999993993e-1f) *
              t +
          3.3333331174e-1f);
  y = y * t * z;
  y = y + fe * -2.12194440e-4f;
  y = y - 0.5f * z;
  return t + y + fe * 0.693359375f;
}

}  // namespace
}  // namespace cropsight::segmentation::simd
