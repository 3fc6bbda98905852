// Integral-image normals (covariance method), reproducing pcl::IntegralImageNormalEstimation
// (COVARIANCE_MATRIX, BORDER_POLICY_IGNORE, no depth-dependent smoothing) step by step:
//  1. depth-change map: PCL's rule, including its treatment of the last row/column;
//  2. chamfer distance (1, 1.4) to the nearest depth change, PCL's two passes on the flat array;
//  3. per pixel, window s = int(min(distance, smoothing)), sums from integral images of
//     n, x, y, z, xx, xy, xz, yy, yz, zz (double), scatter matrix, smallest eigenpair.
// Differences from PCL, on purpose: the integral images are a ring of S+2 rows instead of the
// whole image (keeps them in cache), second moments are accumulated in double (PCL multiplies in
// float) and the scatter matrix stays in double (PCL subtracts in float, which loses digits), and
// the eigenpair comes from Newton's method on the characteristic polynomial instead of PCL's
// trigonometric closed form (no transcendental call per pixel), in float after centring, in a
// branch-free loop over each row's list of pixels that need a normal (valid, with a window, and
// selected when the caller passes a selection), which the compiler vectorises; the window sums and
// centring run in 4-lane double vectors (scatter_row), lane by lane the scalar operations. Invalid and
// unselected pixels skip step 3's window sums and the solver entirely.
#include "cropsight/geometry/integral_normals.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

#include "core/cpu_dispatch.hpp"
#include "cropsight/core/error.hpp"

namespace cropsight::geometry {

namespace {

constexpr int kSums = 10;  // n, x, y, z, xx, xy, xz, yy, yz, zz
constexpr int kCell = 12;  // doubles per integral-image cell: the 10 sums + 2 padding (three 4-lane vectors)

typedef double v4d __attribute__((vector_size(32)));
typedef float v4f __attribute__((vector_size(16)));
typedef int v4i __attribute__((vector_size(16)));

// Lane-wise conversions, written element by element: GCC 12 turns these into one vcvtps2pd /
// vcvtpd2ps in the AVX2 clones, but __builtin_convertvector into two halves through the stack.
// (Out-parameters: a function returning a 32-byte vector changes the ABI of the baseline build.)
inline void to_double(v4f f, v4d& d) { d = v4d{double(f[0]), double(f[1]), double(f[2]), double(f[3])}; }
inline v4f to_float(v4d d) { return v4f{float(d[0]), float(d[1]), float(d[2]), float(d[3])}; }

// The transpose of four 4-lane rows (a, b, c, d): out[j] = {a[j], b[j], c[j], d[j]}.
inline void transpose4(v4d a, v4d b, v4d c, v4d d, v4d out[4]) {
  const v4d t0 = __builtin_shufflevector(a, b, 0, 4, 2, 6), t1 = __builtin_shufflevector(a, b, 1, 5, 3, 7);
  const v4d t2 = __builtin_shufflevector(c, d, 0, 4, 2, 6), t3 = __builtin_shufflevector(c, d, 1, 5, 3, 7);
  out[0] = __builtin_shufflevector(t0, t2, 0, 1, 4, 5), out[1] = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
  out[2] = __builtin_shufflevector(t0, t2, 2, 3, 6, 7), out[3] = __builtin_shufflevector(t1, t3, 2, 3, 6, 7);
}

// One pixel's step of build_row(): adds its cell (three 4-lane vectors) to the running row sums
// and writes up + sums to out.
inline void add_cell(v4d& a0, v4d& a1, v4d& a2, v4d p0, v4d p1, v4d p2, const double* up, double* out) {
  a0 += p0, a1 += p1, a2 += p2;
  v4d u0, u1, u2;
  __builtin_memcpy(&u0, up, 32), __builtin_memcpy(&u1, up + 4, 32), __builtin_memcpy(&u2, up + 8, 32);
  u0 += a0, u1 += a1, u2 += a2;
  __builtin_memcpy(out, &u0, 32), __builtin_memcpy(out + 4, &u1, 32), __builtin_memcpy(out + 8, &u2, 32);
}

// One integral row: out[u + 1] = up[u + 1] + (sums over columns <= u of image row (xr, yr, zr)),
// out[0] = 0. A pixel's cell is (n, x, y, z), (xx, xy, xz, yy), (yz, zz, 0, 0): four pixels'
// values are computed at once, one sum per vector across the pixels (float test, conversion to
// double, double products), then transposed into cells; the cells are added pixel by pixel in
// column order, each lane the same double additions as a scalar loop over the 10 sums (AVX2
// clone at run time; SSE pairs otherwise).
CROPSIGHT_AVX2_CLONES void build_row(int w, const float* __restrict xr, const float* __restrict yr,
                                     const float* __restrict zr, const double* __restrict up, double* __restrict out) {
  v4d a0 = {0, 0, 0, 0}, a1 = {0, 0, 0, 0}, a2 = {0, 0, 0, 0};
  const v4d zero = {0, 0, 0, 0};
  for (int q = 0; q < kCell; ++q) out[q] = 0.0;
  int u = 0;
  for (; u + 4 <= w; u += 4) {
    v4f fx, fy, fz;
    __builtin_memcpy(&fx, xr + u, 16), __builtin_memcpy(&fy, yr + u, 16), __builtin_memcpy(&fz, zr + u, 16);
    // Non-finite points add nothing (PCL's isfinite(x + y + z) test): s - s is 0 only for finite s.
    const v4f s = fx + fy + fz;
    const v4i fin = (s - s) == (v4f){0, 0, 0, 0};
    const v4f f0 = {0, 0, 0, 0}, f1 = {1, 1, 1, 1};
    v4d n, x, y, z;
    to_double(fin ? f1 : f0, n), to_double(fin ? fx : f0, x), to_double(fin ? fy : f0, y);
    to_double(fin ? fz : f0, z);
    v4d c0[4], c1[4];
    transpose4(n, x, y, z, c0);
    transpose4(x * x, x * y, x * z, y * y, c1);
    const v4d yz = y * z, zz = z * z;
    const v4d lo = __builtin_shufflevector(yz, zz, 0, 4, 1, 5), hi = __builtin_shufflevector(yz, zz, 2, 6, 3, 7);
    const v4d c2[4] = {__builtin_shufflevector(lo, zero, 0, 1, 4, 5), __builtin_shufflevector(lo, zero, 2, 3, 4, 5),
                       __builtin_shufflevector(hi, zero, 0, 1, 4, 5), __builtin_shufflevector(hi, zero, 2, 3, 4, 5)};
    for (int j = 0; j < 4; ++j) {
      const std::size_t cell = std::size_t(u + j + 1) * kCell;
      add_cell(a0, a1, a2, c0[j], c1[j], c2[j], up + cell, out + cell);
    }
  }
  for (; u < w; ++u) {
    const bool fin = std::isfinite(xr[u] + yr[u] + zr[u]);
    const double x = fin ? xr[u] : 0.0, y = fin ? yr[u] : 0.0, z = fin ? zr[u] : 0.0;
    const v4d p0 = {fin ? 1.0 : 0.0, x, y, z}, p1 = {x * x, x * y, x * z, y * y}, p2 = {y * z, z * z, 0.0, 0.0};
    const std::size_t cell = std::size_t(u + 1) * kCell;
    add_cell(a0, a1, a2, p0, p1, p2, up + cell, out + cell);
  }
}

// The window sums of pixel k: w[0] = n, x, y, z; w[1] = xx, xy, xz, yy; w[2] = yz, zz, -, -, each
// (c1 + a0 - a1 - c0) from the corner cells of integral rows tops[s] and bottoms[s].
inline void window_sums(int k, const int* __restrict cols, const int* __restrict sizes, const double* const* tops,
                        const double* const* bottoms, v4d w[3]) {
  const int s = sizes[k], left = cols[k] - (s >> 1);  // s >= 2: the shift is s / 2
  const double* a0 = tops[s] + std::size_t(left) * kCell;
  const double* a1 = tops[s] + std::size_t(left + s) * kCell;
  const double* c0 = bottoms[s] + std::size_t(left) * kCell;
  const double* c1 = bottoms[s] + std::size_t(left + s) * kCell;
  for (int j = 0; j < 3; ++j) {
    v4d p, q, r, t;
    __builtin_memcpy(&p, c1 + 4 * j, 32), __builtin_memcpy(&q, a0 + 4 * j, 32);
    __builtin_memcpy(&r, a1 + 4 * j, 32), __builtin_memcpy(&t, c0 + 4 * j, 32);
    w[j] = p + q - r - t;
  }
}

// Window sums and centred scatter matrices of the `count` listed pixels of one row: pixel k at
// column cols[k] with window side sizes[k] reads the corner cells of integral rows tops[s] and
// bottoms[s]; writes xx, xy, xz, yy, yz, zz to m[j * stride + k] (float). Four pixels at a time:
// their sums are transposed into one vector per sum across the pixels, and each entry is
// q - (p·p')·(1/n) in 4-lane double vectors, lane by lane the scalar operations (AVX2 clone at
// run time; no FMA), so the values are those of a scalar loop. cols and sizes hold whole blocks
// of four (list_row() pads them); of the last block only the first pixels are stored.
CROPSIGHT_AVX2_CLONES void scatter_row(int count, const int* __restrict cols, const int* __restrict sizes,
                                       const double* const* tops, const double* const* bottoms, float* __restrict m,
                                       std::size_t stride, double min_valid_fraction) {
  for (int k = 0; k < count; k += 4) {
    v4d w[4][3];
    for (int j = 0; j < 4; ++j) window_sums(k + j, cols, sizes, tops, bottoms, w[j]);
    v4d s0[4], s1[4];  // n, x, y, z and xx, xy, xz, yy, one vector across the four pixels each
    transpose4(w[0][0], w[1][0], w[2][0], w[3][0], s0);
    transpose4(w[0][1], w[1][1], w[2][1], w[3][1], s1);
    const v4d lo = __builtin_shufflevector(w[0][2], w[1][2], 0, 4, 1, 5);
    const v4d hi = __builtin_shufflevector(w[2][2], w[3][2], 0, 4, 1, 5);
    const v4d yz = __builtin_shufflevector(lo, hi, 0, 1, 4, 5), zz = __builtin_shufflevector(lo, hi, 2, 3, 6, 7);
    const v4d one = {1, 1, 1, 1}, ic = one / s0[0];
    const v4d x = s0[1], y = s0[2], z = s0[3];
    v4d c[6] = {s1[0] - x * x * ic, s1[1] - x * y * ic, s1[2] - x * z * ic,
                s1[3] - y * y * ic, yz - y * z * ic,    zz - z * z * ic};
    // Too few valid points in the window (only possible when NaN pixels do not break windows):
    // a zero matrix, which solve_row() turns into NaN.
    v4d side;
    for (int j = 0; j < 4; ++j) side[j] = double(sizes[k + j]);
    const v4d mvf = {min_valid_fraction, min_valid_fraction, min_valid_fraction, min_valid_fraction};
    const auto few = s0[0] < mvf * side * side;
    const int n = std::min(4, count - k);
    for (int e = 0; e < 6; ++e) {
      c[e] = few ? (v4d){0, 0, 0, 0} : c[e];
      const v4f f = to_float(c[e]);
      float* out = m + std::size_t(e) * stride + k;
      if (n == 4)
        __builtin_memcpy(out, &f, 16);
      else
        for (int j = 0; j < n; ++j) out[j] = f[j];
    }
  }
}

// Smallest eigenpair of the scatter matrices of a list of pixels (those of one row that need a
// normal), structure of arrays: m[0..5][i] = xx, xy, xz, yy, yz, zz of pixel i (float, already
// centred in double), p = its position. Writes the unit normal (towards the camera)
// and λ0/trace, or NaN. Branch-free over i so that it vectorises; compiled for AVX2 and for the
// baseline ISA, picked at run time (target_clones).
//  - eigenvalue: the matrix is scaled to trace 1 and λ0 is the smallest root of
//    p(λ) = λ³ - λ² + c1·λ - c0; p is increasing and concave left of λ0 ≤ 1/3, so Newton's method
//    from 0 climbs monotonically to λ0 (quadratically for a simple root) — 6 steps reach float
//    precision unless λ0 ≈ λ1, where the normal is ill-defined anyway;
//  - eigenvector: the longest cross product of two rows of (A - λ0·I) (PCL's eigen33 does the same).
CROPSIGHT_AVX2_CLONES void solve_row(int n, const float* __restrict m, std::size_t stride, const float* __restrict px,
                                     const float* __restrict py, const float* __restrict pz, float* __restrict nx,
                                     float* __restrict ny, float* __restrict nz, float* __restrict cv) {
  const float* M0 = m;
  const float* M1 = m + stride;
  const float* M2 = m + 2 * stride;
  const float* M3 = m + 3 * stride;
  const float* M4 = m + 4 * stride;
  const float* M5 = m + 5 * stride;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int i = 0; i < n; ++i) {
    const float tr0 = M0[i] + M3[i] + M5[i];
    const float sc = 1.0f / (tr0 > 0.0f ? tr0 : 1.0f);
    const float a = M0[i] * sc, b = M1[i] * sc, c = M2[i] * sc, d = M3[i] * sc, e = M4[i] * sc, f = M5[i] * sc;
    const float c1 = a * d - b * b + a * f - c * c + d * f - e * e;
    const float c0 = a * (d * f - e * e) - b * (b * f - c * e) + c * (b * e - c * d);
    // Six Newton steps, written out so that the loop body has no inner loop (vectorisable).
    auto newton = [c0, c1](float l) {
      const float p = ((l - 1.0f) * l + c1) * l - c0;
      const float dp = (3.0f * l - 2.0f) * l + c1;
      const float safe = dp > 0.0f ? dp : 1.0f;  // unconditional division: keeps the loop branch-free
      const float step = p / safe;
      return dp > 0.0f ? l - step : l;
    };
    const float l = newton(newton(newton(newton(newton(newton(0.0f))))));
    const float m00 = a - l, m11 = d - l, m22 = f - l;
    const float r01x = b * e - c * m11, r01y = c * b - m00 * e, r01z = m00 * m11 - b * b;
    const float r02x = b * m22 - c * e, r02y = c * c - m00 * m22, r02z = m00 * e - b * c;
    const float r12x = m11 * m22 - e * e, r12y = e * c - b * m22, r12z = b * e - m11 * c;
    const float n01 = r01x * r01x + r01y * r01y + r01z * r01z;
    const float n02 = r02x * r02x + r02y * r02y + r02z * r02z;
    const float n12 = r12x * r12x + r12y * r12y + r12z * r12z;
    // Longest of the three (ties: the earlier one, as PCL's eigen33), as independent selects.
    float x = r12x, y = r12y, z = r12z, nn = n12;
    const bool t02 = n02 >= nn;
    x = t02 ? r02x : x, y = t02 ? r02y : y, z = t02 ? r02z : z, nn = t02 ? n02 : nn;
    const bool t01 = n01 >= nn;
    x = t01 ? r01x : x, y = t01 ? r01y : y, z = t01 ? r01z : z, nn = t01 ? n01 : nn;
    const bool good = (tr0 > 0.0f) & (nn > 1e-30f);
    const float inv = 1.0f / std::sqrt(nn > 1e-30f ? nn : 1.0f);
    // Towards the viewpoint (camera origin): (0 - p)·n ≥ 0.
    const float flip = (px[i] * x + py[i] * y + pz[i] * z) > 0.0f ? -inv : inv;
    nx[i] = good ? x * flip : nan;
    ny[i] = good ? y * flip : nan;
    nz[i] = good ? z * flip : nan;
    cv[i] = good ? std::max(l, 0.0f) : nan;
  }
}

// One sweep of the chamfer distance along a row (forward: c[i] = min(t[i], c[i-1] + 1) for
// i = 1..w-1, c[0] = t[0]; the backward sweep is the same on the reversed row), computed without
// the sequential dependency: c[i] = min over j of g^j(t[i-j]) with g(x) = fl(x + 1), because
// fl(· + 1) is monotone, so fl(min(a, b) + 1) = min(fl(a + 1), fl(b + 1)); the same float sums as
// the sequential loop, hence bit-identical. Terms with j >= `reach` exceed the cap that every t
// is below, so only j < reach matter. By doubling: after the stages with shifts 1, 2, 4, ..., K
// (stage K: c[i] = min(c[i], g^K(c_prev[i-K])), K sequential additions) c covers j = 0..2K-1;
// each stage is one vectorised pass over the row. `a` is a scratch row of w floats.
// Each stage reads the row from `src` and writes it to `dst` (the two buffers swap roles from
// stage to stage: no copy of the row per stage).
template <int K>
inline void sweep_stage_forward(int w, const float* __restrict src, float* __restrict dst) {
  for (int i = 0; i < K && i < w; ++i) dst[i] = src[i];
  for (int i = K; i < w; ++i) {
    float v = src[i - K];
    for (int m = 0; m < K; ++m) v = v + 1.0f;  // g^K: K roundings, as the sequential loop does
    dst[i] = std::min(src[i], v);
  }
}
template <int K>
inline void sweep_stage_backward(int w, const float* __restrict src, float* __restrict dst) {
  for (int i = 0; i + K < w; ++i) {
    float v = src[i + K];
    for (int m = 0; m < K; ++m) v = v + 1.0f;
    dst[i] = std::min(src[i], v);
  }
  for (int i = std::max(w - K, 0); i < w; ++i) dst[i] = src[i];
}
// Stages with a run-time shift, for smoothing sizes beyond 15 pixels.
inline void sweep_stage_generic(int w, int k, bool forward, const float* __restrict src, float* __restrict dst) {
  for (int i = 0; i < w; ++i) {
    const int from = forward ? i - k : i + k;
    float v = src[i];
    if (from >= 0 && from < w) {
      v = src[from];
      for (int m = 0; m < k; ++m) v = v + 1.0f;
      v = std::min(src[i], v);
    }
    dst[i] = v;
  }
}
CROPSIGHT_AVX2_CLONES void sweep(int w, float* __restrict c, int reach, bool forward, float* __restrict a) {
  // After the stages with shifts 1..K, j = 0..2K-1 is covered; stop once that reaches reach - 1.
  if (reach <= 0) return;
  float* src = c;
  float* dst = a;
  auto next = [&] { std::swap(src, dst); };
  if (forward) {
    sweep_stage_forward<1>(w, src, dst), next();
    if (reach > 2) sweep_stage_forward<2>(w, src, dst), next();
    if (reach > 4) sweep_stage_forward<4>(w, src, dst), next();
    if (reach > 8) sweep_stage_forward<8>(w, src, dst), next();
  } else {
    sweep_stage_backward<1>(w, src, dst), next();
    if (reach > 2) sweep_stage_backward<2>(w, src, dst), next();
    if (reach > 4) sweep_stage_backward<4>(w, src, dst), next();
    if (reach > 8) sweep_stage_backward<8>(w, src, dst), next();
  }
  for (int k = 16; reach > k; k *= 2) sweep_stage_generic(w, k, forward, src, dst), next();
  if (src != c) std::copy(src, src + w, c);  // an odd number of stages ended in the scratch row
}

// The vertical part of a chamfer pass for pixels [lo, hi) of a row, in place: c[i] = min(a[i-1] +
// 1.4, a[i] + 1, a[i+1] + 1.4, c[i]) with `a` the neighbouring row (its reads may run one element
// past either end, into c[0] or c[w-1], which this call does not write, as PCL's flat-array
// passes do; so restrict holds). Vectorised (AVX2 clone at run time).
CROPSIGHT_AVX2_CLONES void vertical_pass(int lo, int hi, const float* __restrict a, float* __restrict c) {
  for (int i = lo; i < hi; ++i)
    c[i] = std::min(std::min(a[i - 1] + 1.4f, a[i] + 1.0f), std::min(a[i + 1] + 1.4f, c[i]));
}

// Throws Error("normals", ...) for a configuration or selection compute() cannot use.
void check_inputs(const IntegralNormalConfig& cfg, std::span<const int> select, std::size_t n) {
  if (!(cfg.normal_smoothing_size >= 1.0f) || !std::isfinite(cfg.normal_smoothing_size))
    throw Error("normals", "normal_smoothing_size must be at least 1 pixel");
  if (!(cfg.max_depth_change_factor >= 0.0f)) throw Error("normals", "max_depth_change_factor must be >= 0");
  if (!(cfg.min_valid_fraction >= 0.0f && cfg.min_valid_fraction <= 1.0f))
    throw Error("normals", "min_valid_fraction must be in [0, 1]");
  if (!select.empty() && select.size() != n) throw Error("normals", "selection size differs from the cloud size");
}

// NaN in n floats of each of the four outputs from offset a (AVX2 clone at run time: 8 floats a
// store instead of the baseline's 4).
CROPSIGHT_AVX2_CLONES void fill_nan4(float* __restrict nx, float* __restrict ny, float* __restrict nz,
                                     float* __restrict cv, std::size_t n) {
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  for (std::size_t i = 0; i < n; ++i) nx[i] = kNaN, ny[i] = kNaN, nz[i] = kNaN, cv[i] = kNaN;
}

// NaN in rows [v0, v1) of the four outputs.
void nan_rows(OrganizedCloud& cloud, int v0, int v1) {
  const std::size_t a = std::size_t(v0) * cloud.width, n = std::size_t(v1 - v0) * cloud.width;
  fill_nan4(cloud.nx.data() + a, cloud.ny.data() + a, cloud.nz.data() + a, cloud.curvature.data() + a, n);
}

// Step 1. Depth-change map, PCL's rule: for ri < h-1, ci < w-1 the pixel is compared with its
// right (H) and lower (V) neighbour, and a failed test marks both pixels. So the last column is
// only compared with its left neighbour and the last row with the row above. Computed per row
// as flags (branch-free, vectorised), then combined into the chamfer distance's start values
// (step 2): dist[i] = cap where pixel i is no depth change, 0 where it is.
CROPSIGHT_AVX2_CLONES void depth_change_map(const float* Z, int w, int h, float factor, bool nan_breaks, float cap,
                                            std::vector<float>& distance, std::vector<std::uint8_t>& flags) {
  const bool nan_ok = !nan_breaks;
  distance.resize(std::size_t(w) * std::size_t(h));
  flags.assign(3 * std::size_t(w), 0);
  std::uint8_t* H = flags.data();  // this row: pixel vs right neighbour failed
  std::uint8_t* V = H + w;         // this row: pixel vs lower neighbour failed
  std::uint8_t* Vprev = V + w;     // previous row's V
  float* dist = distance.data();
  for (int ri = 0; ri < h; ++ri) {
    const float* z0 = Z + std::size_t(ri) * w;
    if (ri < h - 1) {
      const float* z1 = z0 + w;
      for (int ci = 0; ci < w - 1; ++ci) {
        const float depth = z0[ci], depth_r = z0[ci + 1], depth_d = z1[ci];
        const float limit = factor * (std::abs(depth) + 1.0f) * 2.0f;
        const bool fin = std::isfinite(depth);
        // "!(a <= b)" is true for NaN, like PCL's "fabs(..) > limit || !isfinite(..)" chain.
        // With nan_breaks off, a pair with a NaN is no depth change (the NaN adds nothing to the sums).
        const bool fin_r = std::isfinite(depth_r), fin_d = std::isfinite(depth_d);
        H[ci] = std::uint8_t(nan_ok ? (fin & fin_r & !(std::fabs(depth - depth_r) <= limit))
                                    : (!(std::fabs(depth - depth_r) <= limit) | !fin | !fin_r));
        V[ci] = std::uint8_t(nan_ok ? (fin & fin_d & !(std::fabs(depth - depth_d) <= limit))
                                    : (!(std::fabs(depth - depth_d) <= limit) | !fin | !fin_d));
      }
      H[w - 1] = V[w - 1] = 0;
    } else {
      std::fill(H, H + w, std::uint8_t(0));
      std::fill(V, V + w, std::uint8_t(0));
    }
    float* d = dist + std::size_t(ri) * w;
    d[0] = (H[0] | V[0] | Vprev[0]) ? 0.0f : cap;
    for (int ci = 1; ci < w; ++ci) d[ci] = (H[ci] | H[ci - 1] | V[ci] | Vprev[ci]) ? 0.0f : cap;
    std::copy(V, V + w, Vprev);
  }
}

// Step 2. Chamfer distance map (1, 1.4), PCL's two passes on the flat array (including its row-end
// reads that wrap into the neighbouring row). Values are capped at `cap` (= smoothing size):
// the passes are a min-plus recursion, so capping the start values gives min(PCL's value, cap),
// and only min(distance, smoothing) is used, and min(min(PCL, cap), smoothing) = min(PCL,
// smoothing). Each row is split into a vectorised part (the three neighbours in the previous row)
// and the sweep along the row (vectorised too, same float sums as PCL's sequential loop).
// `distance` holds the start values (depth_change_map()) and is turned into the map in place.
void chamfer_distance(int w, int h, float cap, std::vector<float>& distance, std::vector<float>& scratch) {
  const int reach = int(cap) + 1;  // g^j(x) >= j - tiny > cap for j >= reach
  scratch.resize(std::size_t(w));
  float* dist = distance.data();
  float* sa = scratch.data();  // the sweep's scratch row
  for (int ri = 1; ri < h; ++ri) {
    const float* prev = dist + std::size_t(ri - 1) * w;
    float* cur = dist + std::size_t(ri) * w;
    vertical_pass(1, w, prev, cur);  // prev[w] is cur[0] (not written here), as in PCL
    sweep(w, cur, reach, true, sa);
  }
  for (int ri = h - 2; ri >= 0; --ri) {
    float* cur = dist + std::size_t(ri) * w;
    const float* next = cur + w;
    vertical_pass(0, w - 1, next, cur);  // next[-1] is cur[w-1] (not written here), as in PCL
    sweep(w, cur, reach, false, sa);
  }
}

// Step 3's integral images: a ring of integral rows I(r), r = 0..h: I(r)[u] = sums over rows < r
// and columns < u, each cell kCell consecutive doubles (the kSums sums + padding; contiguous
// corner reads). Pixel row v reads rows v - S/2 .. v + S - S/2 (S + 1 rows), so S + 2 slots
// suffice. Rows are built on demand, in order.
class IntegralRing {
 public:
  IntegralRing(std::vector<double>& storage, int w, int S, const float* X, const float* Y, const float* Z)
      : w_(w), ring_(S + 2), row_len_(std::size_t(w + 1) * kCell), X_(X), Y_(Y), Z_(Z) {
    // Only I(0) must start as zeros: build_row() writes every cell of the other slots before
    // they are read, so the rest of the buffer keeps what the last frame left in it.
    storage.resize(row_len_ * ring_);
    data_ = storage.data();
    std::fill(data_, data_ + row_len_, 0.0);
  }
  const double* row(int r) const { return data_ + std::size_t(r % ring_) * row_len_; }
  // Builds I(built) .. I(r_last).
  void build_until(int r_last) {
    for (; built_ <= r_last; ++built_) {
      const int r = built_ - 1;  // image row added by I(built)
      const std::size_t o = std::size_t(r) * w_;
      build_row(w_, X_ + o, Y_ + o, Z_ + o, row(r), slot(built_));
    }
  }

 private:
  double* slot(int r) { return data_ + std::size_t(r % ring_) * row_len_; }
  int w_, ring_;
  std::size_t row_len_;
  const float *X_, *Y_, *Z_;
  double* data_ = nullptr;
  int built_ = 1;  // I(0) (zeros) is in slot 0
};

// Step 3's per-row work space, structure of arrays over the pixels of one row that get a normal:
// 6 scatter planes, 3 positions, 4 results, their columns and window sizes.
struct RowLists {
  std::size_t stride;
  float *M, *PX, *PY, *PZ, *RX, *RY, *RZ, *RC;
  int *cols, *sizes;
  RowLists(std::vector<float>& row, std::vector<int>& cols_v, std::vector<int>& sizes_v, int run)
      : stride(std::size_t(run)) {
    row.resize(13 * stride);
    cols_v.resize(stride + 3);  // + 3: list_row() pads the lists to whole blocks of 4 for scatter_row()
    sizes_v.resize(stride + 3);
    M = row.data();
    PX = M + 6 * stride, PY = PX + stride, PZ = PY + stride;
    RX = PZ + stride, RY = RX + stride, RZ = RY + stride, RC = RZ + stride;
    cols = cols_v.data(), sizes = sizes_v.data();
  }
};

// The pixels of row v (o = v·w) that get a normal: valid, window larger than 2, selected (when
// `sel`). Two passes: need[k] = 1 for pixel u = S + k that does, for the row's w - 2S pixels
// (branch-free, vectorised: & instead of &&; NaN points have distance 0, so the window test also
// skips them), then the compaction, a 64-bit word of `need` at a time (most words of a sparse
// selection are zero), writing their columns and window sizes int(min(distance, smoothing)) in
// column order, with their positions; returns how many.
CROPSIGHT_AVX2_CLONES void need_row(const float* __restrict Z, const float* __restrict dist, const int* __restrict sel,
                                    int m, float smoothing, std::uint8_t* __restrict need) {
  if (sel) {
    for (int k = 0; k < m; ++k)
      need[k] = std::uint8_t(std::isfinite(Z[k]) & (std::min(dist[k], smoothing) > 2.0f) & (sel[k] >= 0));
  } else {
    for (int k = 0; k < m; ++k) need[k] = std::uint8_t(std::isfinite(Z[k]) & (std::min(dist[k], smoothing) > 2.0f));
  }
}
int list_row(const float* const xyz[3], const float* dist, const int* sel, std::size_t o, int w, int S, float smoothing,
             std::uint8_t* need, const RowLists& L) {
  const int m = w - 2 * S;
  const std::size_t first = o + std::size_t(S);
  need_row(xyz[2] + first, dist + first, sel ? sel + first : nullptr, m, smoothing, need);
  const float* d = dist + first;
  const float *x = xyz[0] + first, *y = xyz[1] + first, *z = xyz[2] + first;
  int count = 0;
  auto take = [&](int k) {  // also the pixel's position, for solve_row()
    L.cols[count] = S + k, L.sizes[count] = int(std::min(d[k], smoothing));
    L.PX[count] = x[k], L.PY[count] = y[k], L.PZ[count] = z[k];
    ++count;
  };
  int k0 = 0;
  for (; k0 + 8 <= m; k0 += 8) {
    std::uint64_t word;
    std::memcpy(&word, need + k0, 8);
    for (; word != 0; word &= word - 1) take(k0 + std::countr_zero(word) / 8);  // bytes are 0 or 1
  }
  for (; k0 < m; ++k0)
    if (need[k0]) take(k0);
  // Pad the columns and sizes to a whole block of four with copies of the last pixel, so that
  // scatter_row() reads four valid entries per block (it stores only the first `count`).
  for (int k = count; k % 4 != 0; ++k) L.cols[k] = L.cols[count - 1], L.sizes[k] = L.sizes[count - 1];
  return count;
}

}  // namespace

IntegralNormalEstimator::IntegralNormalEstimator(IntegralNormalConfig cfg) : cfg_(cfg) {}

void IntegralNormalEstimator::compute(OrganizedCloud& cloud, std::span<const int> select) {
  check_inputs(cfg_, select, cloud.size());
  const int w = cloud.width, h = cloud.height;
  const std::size_t n = cloud.size();
  // Every pixel of the four outputs is written below: NaN row by row just before the row's
  // results (the row is then still in cache when they are scattered into it), the border rows
  // and the early return at once.
  cloud.nx.resize(n);
  cloud.ny.resize(n);
  cloud.nz.resize(n);
  cloud.curvature.resize(n);
  const int S = int(cfg_.normal_smoothing_size);
  if (w < 2 || h < 2 || 2 * S >= w || 2 * S >= h) {  // nothing outside the ignored border
    nan_rows(cloud, 0, h);
    return;
  }
  nan_rows(cloud, 0, S);
  nan_rows(cloud, h - S, h);
  const float* X = cloud.x.data();
  const float* Y = cloud.y.data();
  const float* Z = cloud.z.data();

  depth_change_map(Z, w, h, cfg_.max_depth_change_factor, cfg_.nan_breaks_window, cfg_.normal_smoothing_size, distance_,
                   flags_);
  chamfer_distance(w, h, cfg_.normal_smoothing_size, distance_, scratch_);
  const float* dist = distance_.data();

  // Step 3. Per row: the list of pixels that get a normal, their window sums and scatter
  // matrices (one scalar pass: the window size varies near depth changes), then solve_row() on
  // the compacted list (vectorised) and a scatter of the results. Invalid and unselected pixels
  // cost one test each.
  IntegralRing integral(integral_, w, S, X, Y, Z);
  const RowLists L(row_, cols_, sizes_, w - 2 * S);
  float* NX = cloud.nx.data();
  float* NY = cloud.ny.data();
  float* NZ = cloud.nz.data();
  float* CV = cloud.curvature.data();
  const int* sel = select.empty() ? nullptr : select.data();
  const float* const xyz[3] = {X, Y, Z};
  // Integral rows of each window size s = 2..S for the current pixel row (sm > 2 gives s >= 2).
  std::vector<const double*> tops(std::size_t(S) + 1, nullptr), bottoms(std::size_t(S) + 1, nullptr);
  for (int v = S; v < h - S; ++v) {
    const std::size_t o = std::size_t(v) * w;
    nan_rows(cloud, v, v + 1);
    // flags_ (the depth-change map's 3w bytes, free by now) holds the row's "needs a normal" bytes.
    const int count = list_row(xyz, dist, sel, o, w, S, cfg_.normal_smoothing_size, flags_.data(), L);
    if (count == 0) continue;
    integral.build_until(v + S - S / 2);
    // Window rows per size: top v - s/2, bottom v - s/2 + s.
    for (int s = 2; s <= S; ++s)
      tops[std::size_t(s)] = integral.row(v - s / 2), bottoms[std::size_t(s)] = integral.row(v - s / 2 + s);
    scatter_row(count, L.cols, L.sizes, tops.data(), bottoms.data(), L.M, L.stride,
                cfg_.nan_breaks_window ? 0.0 : double(cfg_.min_valid_fraction));
    solve_row(count, L.M, L.stride, L.PX, L.PY, L.PZ, L.RX, L.RY, L.RZ, L.RC);
    for (int k = 0; k < count; ++k) {
      const std::size_t i = o + L.cols[k];
      NX[i] = L.RX[k], NY[i] = L.RY[k], NZ[i] = L.RZ[k], CV[i] = L.RC[k];
    }
  }
}

void estimate_normals_integral(OrganizedCloud& cloud, const IntegralNormalConfig& cfg) {
  IntegralNormalEstimator est(cfg);
  est.compute(cloud);
}

}  // namespace cropsight::geometry
