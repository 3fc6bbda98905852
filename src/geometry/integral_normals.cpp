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
// branch-free loop over each row that the compiler vectorises.
#include "cropsight/geometry/integral_normals.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cropsight/core/error.hpp"

namespace cropsight::geometry {

namespace {

constexpr int kSums = 10;  // n, x, y, z, xx, xy, xz, yy, yz, zz

// Smallest eigenpair of the scatter matrices of one row of pixels, structure of arrays:
// m[0..5][i] = xx, xy, xz, yy, yz, zz of pixel i (float, already centred in double), p = its
// position, ok = whether pixel i has a window at all. Writes the unit normal (towards the camera)
// and λ0/trace, or NaN. Branch-free over i so that it vectorises; compiled for AVX2 and for the
// baseline ISA, picked at run time (target_clones).
//  - eigenvalue: the matrix is scaled to trace 1 and λ0 is the smallest root of
//    p(λ) = λ³ - λ² + c1·λ - c0; p is increasing and concave left of λ0 ≤ 1/3, so Newton's method
//    from 0 climbs monotonically to λ0 (quadratically for a simple root) — 6 steps reach float
//    precision unless λ0 ≈ λ1, where the normal is ill-defined anyway;
//  - eigenvector: the longest cross product of two rows of (A - λ0·I) (PCL's eigen33 does the same).
__attribute__((target_clones("avx2", "default"))) void solve_row(int n, const float* __restrict m, std::size_t stride,
                                                                 const float* __restrict px, const float* __restrict py,
                                                                 const float* __restrict pz, const float* __restrict ok,
                                                                 float* __restrict nx, float* __restrict ny,
                                                                 float* __restrict nz, float* __restrict cv) {
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
    const bool good = (ok[i] > 0.5f) & (tr0 > 0.0f) & (nn > 1e-30f);
    const float inv = 1.0f / std::sqrt(nn > 1e-30f ? nn : 1.0f);
    // Towards the viewpoint (camera origin): (0 - p)·n ≥ 0.
    const float flip = (px[i] * x + py[i] * y + pz[i] * z) > 0.0f ? -inv : inv;
    nx[i] = good ? x * flip : nan;
    ny[i] = good ? y * flip : nan;
    nz[i] = good ? z * flip : nan;
    cv[i] = good ? std::max(l, 0.0f) : nan;
  }
}

// Window sums for a row of pixels that all use the full S×S window (pixel k of the run sits at
// column S + k) and their centred scatter matrices, written as floats into six planes of
// `stride`; the caller overwrites the pixels whose window is smaller. Branch-free and unit-stride over k: vectorised
// (AVX2 clone at run time).
__attribute__((target_clones("avx2", "default"))) void full_windows(int run, int off, int S,
                                                                    const double* __restrict top_row,
                                                                    const double* __restrict bottom_row,
                                                                    float* __restrict out, std::size_t stride) {
  // Window of pixel u = S + k: columns [u - S/2, u - S/2 + S) → integral columns u - S/2 and
  // u - S/2 + S, i.e. k + off and k + off + S with off = S - S/2.
  for (int k = 0; k < run; ++k) {
    const double* a0 = top_row + std::size_t(k + off) * kSums;
    const double* a1 = a0 + std::size_t(S) * kSums;
    const double* c0 = bottom_row + std::size_t(k + off) * kSums;
    const double* c1 = c0 + std::size_t(S) * kSums;
    double m[kSums];
    for (int q = 0; q < kSums; ++q) m[q] = c1[q] + a0[q] - a1[q] - c0[q];
    const double ic = 1.0 / (m[0] > 0.5 ? m[0] : 1.0);
    out[k] = float(m[4] - m[1] * m[1] * ic);
    out[stride + k] = float(m[5] - m[1] * m[2] * ic);
    out[2 * stride + k] = float(m[6] - m[1] * m[3] * ic);
    out[3 * stride + k] = float(m[7] - m[2] * m[2] * ic);
    out[4 * stride + k] = float(m[8] - m[2] * m[3] * ic);
    out[5 * stride + k] = float(m[9] - m[3] * m[3] * ic);
  }
}

}  // namespace

IntegralNormalEstimator::IntegralNormalEstimator(IntegralNormalConfig cfg) : cfg_(cfg) {}

void IntegralNormalEstimator::compute(OrganizedCloud& cloud) {
  if (!(cfg_.normal_smoothing_size >= 1.0f) || !std::isfinite(cfg_.normal_smoothing_size))
    throw Error("normals", "normal_smoothing_size must be at least 1 pixel");
  if (!(cfg_.max_depth_change_factor >= 0.0f)) throw Error("normals", "max_depth_change_factor must be >= 0");
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  const int w = cloud.width, h = cloud.height;
  const std::size_t n = cloud.size();
  cloud.nx.assign(n, kNaN);
  cloud.ny.assign(n, kNaN);
  cloud.nz.assign(n, kNaN);
  cloud.curvature.assign(n, kNaN);
  const int S = int(cfg_.normal_smoothing_size);
  if (w < 2 || h < 2 || 2 * S >= w || 2 * S >= h) return;  // nothing outside the ignored border
  const float* X = cloud.x.data();
  const float* Y = cloud.y.data();
  const float* Z = cloud.z.data();

  // 1. Depth-change map, PCL's rule: for ri < h-1, ci < w-1 the pixel is compared with its
  // right (H) and lower (V) neighbour, and a failed test marks both pixels. So the last column is
  // only compared with its left neighbour and the last row with the row above. Computed per row
  // as flags (branch-free, vectorised), then combined.
  change_.assign(n, 1);  // 1 = no depth change
  flags_.assign(3 * std::size_t(w), 0);
  std::uint8_t* H = flags_.data();  // this row: pixel vs right neighbour failed
  std::uint8_t* V = H + w;          // this row: pixel vs lower neighbour failed
  std::uint8_t* Vprev = V + w;      // previous row's V
  std::uint8_t* ch = change_.data();
  const float factor = cfg_.max_depth_change_factor;
  for (int ri = 0; ri < h; ++ri) {
    const float* z0 = Z + std::size_t(ri) * w;
    if (ri < h - 1) {
      const float* z1 = z0 + w;
      for (int ci = 0; ci < w - 1; ++ci) {
        const float depth = z0[ci], depth_r = z0[ci + 1], depth_d = z1[ci];
        const float limit = factor * (std::abs(depth) + 1.0f) * 2.0f;
        const bool fin = std::isfinite(depth);
        // "!(a <= b)" is true for NaN, like PCL's "fabs(..) > limit || !isfinite(..)" chain.
        H[ci] = std::uint8_t(!(std::fabs(depth - depth_r) <= limit) | !fin | !std::isfinite(depth_r));
        V[ci] = std::uint8_t(!(std::fabs(depth - depth_d) <= limit) | !fin | !std::isfinite(depth_d));
      }
      H[w - 1] = V[w - 1] = 0;
    } else {
      std::fill(H, H + w, std::uint8_t(0));
      std::fill(V, V + w, std::uint8_t(0));
    }
    std::uint8_t* c = ch + std::size_t(ri) * w;
    c[0] = std::uint8_t(!(H[0] | V[0] | Vprev[0]));
    for (int ci = 1; ci < w; ++ci) c[ci] = std::uint8_t(!(H[ci] | H[ci - 1] | V[ci] | Vprev[ci]));
    std::copy(V, V + w, Vprev);
  }

  // 2. Chamfer distance map (1, 1.4), PCL's two passes on the flat array (including its row-end
  // reads that wrap into the neighbouring row). Values are capped at `cap` (> smoothing size):
  // the passes are a min-plus recursion, so capping the start values gives min(PCL's value, cap),
  // and only min(distance, smoothing) is used. Each row is split into a vectorised part (the
  // three neighbours in the previous row) and a sequential sweep along the row, which skips the
  // dependency chain where nothing within reach is closer than the cap.
  const float cap = float(S) + 2.0f;
  distance_.resize(n);
  scratch_.resize(std::size_t(w));
  float* dist = distance_.data();
  float* t = scratch_.data();
  for (std::size_t i = 0; i < n; ++i) dist[i] = ch[i] ? cap : 0.0f;
  for (int ri = 1; ri < h; ++ri) {
    const float* prev = dist + std::size_t(ri - 1) * w;
    float* cur = dist + std::size_t(ri) * w;
    for (int ci = 1; ci < w; ++ci)  // prev[w] is cur[0], as in PCL
      t[ci] = std::min(std::min(prev[ci - 1] + 1.4f, prev[ci] + 1.0f), std::min(prev[ci + 1] + 1.4f, cur[ci]));
    float carry = cur[0] + 1.0f;
    for (int ci = 1; ci < w; ++ci) {
      const float v = carry < cap ? std::min(t[ci], carry) : t[ci];
      cur[ci] = v;
      carry = v + 1.0f;
    }
  }
  for (int ri = h - 2; ri >= 0; --ri) {
    float* cur = dist + std::size_t(ri) * w;
    const float* next = cur + w;
    for (int ci = w - 2; ci >= 0; --ci)  // next[-1] is cur[w-1], as in PCL
      t[ci] = std::min(std::min(next[ci - 1] + 1.4f, next[ci] + 1.0f), std::min(next[ci + 1] + 1.4f, cur[ci]));
    float carry = cur[w - 1] + 1.0f;
    for (int ci = w - 2; ci >= 0; --ci) {
      const float v = carry < cap ? std::min(t[ci], carry) : t[ci];
      cur[ci] = v;
      carry = v + 1.0f;
    }
  }

  // 3. Ring of integral rows I(r), r = 0..h: I(r)[u] = sums over rows < r and columns < u, each
  // cell kSums consecutive doubles (one pointer while building; contiguous corner reads).
  // Pixel row v reads rows v - S/2 .. v + S - S/2 (S + 1 rows), so S + 2 slots suffice.
  const int ring = S + 2;
  const std::size_t row_len = std::size_t(w + 1) * kSums;
  integral_.assign(row_len * ring, 0.0);
  auto irow = [&](int r) { return integral_.data() + std::size_t(r % ring) * row_len; };
  int built = 1;  // I(0) (zeros) is in slot 0
  auto build_until = [&](int r_last) {
    for (; built <= r_last; ++built) {
      const int r = built - 1;  // image row added by I(built)
      const double* up = irow(r);
      double* out = irow(built);
      double acc[kSums] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
      for (int q = 0; q < kSums; ++q) out[q] = 0.0;
      const float* xr = X + std::size_t(r) * w;
      const float* yr = Y + std::size_t(r) * w;
      const float* zr = Z + std::size_t(r) * w;
      for (int u = 0; u < w; ++u) {
        // Non-finite points add nothing (PCL's isfinite(x + y + z) test), without a branch.
        const bool fin = std::isfinite(xr[u] + yr[u] + zr[u]);
        const double x = fin ? xr[u] : 0.0, y = fin ? yr[u] : 0.0, z = fin ? zr[u] : 0.0;
        acc[0] += fin ? 1.0 : 0.0, acc[1] += x, acc[2] += y, acc[3] += z;
        acc[4] += x * x, acc[5] += x * y, acc[6] += x * z, acc[7] += y * y, acc[8] += y * z, acc[9] += z * z;
        const double* a = up + std::size_t(u + 1) * kSums;
        double* o = out + std::size_t(u + 1) * kSums;
        for (int q = 0; q < kSums; ++q) o[q] = a[q] + acc[q];
      }
    }
  };

  // Scatter matrix (centred in double, then float) of the window of side s at top-left (left, top).
  auto scatter = [&](const double* top_row, const double* bottom_row, int left, int s, float* r, std::size_t stride) {
    double m[kSums];
    const double* a0 = top_row + std::size_t(left) * kSums;
    const double* a1 = top_row + std::size_t(left + s) * kSums;
    const double* c0 = bottom_row + std::size_t(left) * kSums;
    const double* c1 = bottom_row + std::size_t(left + s) * kSums;
    for (int q = 0; q < kSums; ++q) m[q] = c1[q] + a0[q] - a1[q] - c0[q];
    const double ic = 1.0 / m[0];
    r[0] = float(m[4] - m[1] * m[1] * ic), r[stride] = float(m[5] - m[1] * m[2] * ic);
    r[2 * stride] = float(m[6] - m[1] * m[3] * ic), r[3 * stride] = float(m[7] - m[2] * m[2] * ic);
    r[4 * stride] = float(m[8] - m[2] * m[3] * ic), r[5 * stride] = float(m[9] - m[3] * m[3] * ic);
  };

  const float smoothing = cfg_.normal_smoothing_size;
  float* NX = cloud.nx.data();
  float* NY = cloud.ny.data();
  float* NZ = cloud.nz.data();
  float* CV = cloud.curvature.data();
  // Per row: window sums with the full window for every pixel (vectorised), then a fix-up pass
  // for the pixels near depth changes whose window is smaller, then solve_row().
  const int run = w - 2 * S;
  const std::size_t stride = std::size_t(run);
  row_.resize(6 * stride);
  ok_.resize(stride);
  for (int v = S; v < h - S; ++v) {
    build_until(v + S - S / 2);
    const double* top_row = irow(v - S / 2);
    const double* bottom_row = irow(v - S / 2 + S);
    full_windows(run, S - S / 2, S, top_row, bottom_row, row_.data(), stride);
    for (int k = 0; k < run; ++k) {
      const int u = S + k;
      const std::size_t i = std::size_t(v) * w + u;
      const float sm = std::min(dist[i], smoothing);
      // NaN points have distance 0, so this also skips them.
      const bool window = std::isfinite(Z[i]) && sm > 2.0f;
      ok_[k] = window ? 1.0f : 0.0f;
      const int s = int(sm);
      if (window && s != S) scatter(irow(v - s / 2), irow(v - s / 2 + s), u - s / 2, s, row_.data() + k, stride);
    }
    const std::size_t o = std::size_t(v) * w + S;
    solve_row(run, row_.data(), stride, X + o, Y + o, Z + o, ok_.data(), NX + o, NY + o, NZ + o, CV + o);
  }
}

void estimate_normals_integral(OrganizedCloud& cloud, const IntegralNormalConfig& cfg) {
  IntegralNormalEstimator est(cfg);
  est.compute(cloud);
}

}  // namespace cropsight::geometry
