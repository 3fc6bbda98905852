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
// trigonometric closed form (no transcendental call per pixel).
#include "cropsight/geometry/integral_normals.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cropsight/core/error.hpp"

namespace cropsight::geometry {

namespace {

constexpr int kSums = 10;  // n, x, y, z, xx, xy, xz, yy, yz, zz

// Smallest eigenpair of the symmetric positive semi-definite scatter matrix
// [a b c; b d e; c e f]. Writes the unit eigenvector and λ0/trace. Returns false when undefined.
inline bool smallest_eigenpair(double a, double b, double c, double d, double e, double f, double& vx, double& vy,
                               double& vz, double& curvature) {
  const double tr = a + d + f;
  if (!(tr > 0.0)) return false;
  const double s = 1.0 / tr;  // scale to trace 1: the eigenvalues lie in [0, 1]
  a *= s, b *= s, c *= s, d *= s, e *= s, f *= s;
  // Characteristic polynomial p(λ) = λ³ - λ² + c1·λ - c0 (trace 1).
  const double c1 = a * d - b * b + a * f - c * c + d * f - e * e;
  const double c0 = a * (d * f - e * e) - b * (b * f - c * e) + c * (b * e - c * d);
  // p is increasing and concave left of its smallest root λ0 ≤ 1/3, so Newton's method started
  // at 0 climbs monotonically to λ0 without overshooting (quadratically when λ0 is simple).
  double l = 0.0;
  for (int it = 0; it < 40; ++it) {
    const double p = ((l - 1.0) * l + c1) * l - c0;
    const double dp = (3.0 * l - 2.0) * l + c1;
    if (!(dp > 0.0)) break;
    const double step = p / dp;
    l -= step;
    if (std::abs(step) <= 1e-13) break;
  }
  // Eigenvector: the largest cross product of two rows of (A - λ0 I) (rank 2 for a simple λ0).
  const double m00 = a - l, m11 = d - l, m22 = f - l;
  const double r01x = b * e - c * m11, r01y = c * b - m00 * e, r01z = m00 * m11 - b * b;  // row0 × row1
  const double r02x = b * m22 - c * e, r02y = c * c - m00 * m22, r02z = m00 * e - b * c;  // row0 × row2
  const double r12x = m11 * m22 - e * e, r12y = e * c - b * m22, r12z = b * e - m11 * c;  // row1 × row2
  const double n01 = r01x * r01x + r01y * r01y + r01z * r01z;
  const double n02 = r02x * r02x + r02y * r02y + r02z * r02z;
  const double n12 = r12x * r12x + r12y * r12y + r12z * r12z;
  double x, y, z, nn;
  if (n01 >= n02 && n01 >= n12) {
    x = r01x, y = r01y, z = r01z, nn = n01;
  } else if (n02 >= n12) {
    x = r02x, y = r02y, z = r02z, nn = n02;
  } else {
    x = r12x, y = r12y, z = r12z, nn = n12;
  }
  if (!(nn > 1e-300)) return false;  // λ0 of multiplicity ≥ 2: no unique normal
  const double inv = 1.0 / std::sqrt(nn);
  vx = x * inv, vy = y * inv, vz = z * inv;
  curvature = std::max(l, 0.0);
  return true;
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

  // 1. Depth-change map (0 = change). Same loops as PCL, so the last column is only compared
  // with its left neighbour and the last row with the row above.
  change_.assign(n, 255);
  const float factor = cfg_.max_depth_change_factor;
  for (int ri = 0; ri < h - 1; ++ri) {
    for (int ci = 0; ci < w - 1; ++ci) {
      const int i = ri * w + ci;
      const float depth = Z[i], depth_r = Z[i + 1], depth_d = Z[i + w];
      const float limit = factor * (std::abs(depth) + 1.0f) * 2.0f;
      if (std::fabs(depth - depth_r) > limit || !std::isfinite(depth) || !std::isfinite(depth_r)) {
        change_[i] = 0;
        change_[i + 1] = 0;
      }
      if (std::fabs(depth - depth_d) > limit || !std::isfinite(depth) || !std::isfinite(depth_d)) {
        change_[i] = 0;
        change_[i + w] = 0;
      }
    }
  }

  // 2. Chamfer distance map, PCL's passes on the flat array (the row-end reads that wrap to the
  // neighbouring row are PCL's behaviour and are kept so that the windows match).
  distance_.resize(n);
  float* dist = distance_.data();
  const float far = float(w + h);
  for (std::size_t i = 0; i < n; ++i) dist[i] = change_[i] == 0 ? 0.0f : far;
  {
    float* prev = dist;
    float* cur = dist + w;
    for (int ri = 1; ri < h; ++ri, prev = cur, cur += w) {
      for (int ci = 1; ci < w; ++ci) {
        const float m =
            std::min(std::min(prev[ci - 1] + 1.4f, prev[ci] + 1.0f), std::min(cur[ci - 1] + 1.0f, prev[ci + 1] + 1.4f));
        if (m < cur[ci]) cur[ci] = m;
      }
    }
    float* next = dist + std::size_t(w) * (h - 1);
    cur = next - w;
    for (int ri = h - 2; ri >= 0; --ri, next = cur, cur -= w) {
      for (int ci = w - 2; ci >= 0; --ci) {
        const float m =
            std::min(std::min(next[ci - 1] + 1.4f, next[ci] + 1.0f), std::min(cur[ci + 1] + 1.0f, next[ci + 1] + 1.4f));
        if (m < cur[ci]) cur[ci] = m;
      }
    }
  }

  // 3. Ring of integral rows I(r), r = 0..h: I(r)[u] = sums over rows < r and columns < u.
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
      for (int k = 0; k < kSums; ++k) out[k] = 0.0;
      const float* xr = X + std::size_t(r) * w;
      const float* yr = Y + std::size_t(r) * w;
      const float* zr = Z + std::size_t(r) * w;
      for (int u = 0; u < w; ++u) {
        const double x = xr[u], y = yr[u], z = zr[u];
        if (std::isfinite(x + y + z)) {
          acc[0] += 1.0, acc[1] += x, acc[2] += y, acc[3] += z;
          acc[4] += x * x, acc[5] += x * y, acc[6] += x * z, acc[7] += y * y, acc[8] += y * z, acc[9] += z * z;
        }
        const double* a = up + std::size_t(u + 1) * kSums;
        double* o = out + std::size_t(u + 1) * kSums;
        for (int k = 0; k < kSums; ++k) o[k] = a[k] + acc[k];
      }
    }
  };

  const float smoothing = cfg_.normal_smoothing_size;
  float* NX = cloud.nx.data();
  float* NY = cloud.ny.data();
  float* NZ = cloud.nz.data();
  float* CV = cloud.curvature.data();
  for (int v = S; v < h - S; ++v) {
    build_until(v + S - S / 2);
    for (int u = S; u < w - S; ++u) {
      const int i = v * w + u;
      if (!std::isfinite(Z[i])) continue;
      const float sm = std::min(dist[i], smoothing);
      if (!(sm > 2.0f)) continue;
      const int s = int(sm);
      const int top = v - s / 2, left = u - s / 2;
      const double* A = irow(top) + std::size_t(left) * kSums;
      const double* B = A + std::size_t(s) * kSums;
      const double* C = irow(top + s) + std::size_t(left) * kSums;
      const double* D = C + std::size_t(s) * kSums;
      double m[kSums];
      for (int k = 0; k < kSums; ++k) m[k] = D[k] + A[k] - B[k] - C[k];
      const double cnt = m[0];
      if (!(cnt > 0.5)) continue;
      const double ic = 1.0 / cnt;
      const double sxx = m[4] - m[1] * m[1] * ic, sxy = m[5] - m[1] * m[2] * ic, sxz = m[6] - m[1] * m[3] * ic;
      const double syy = m[7] - m[2] * m[2] * ic, syz = m[8] - m[2] * m[3] * ic, szz = m[9] - m[3] * m[3] * ic;
      double ex, ey, ez, curv;
      if (!smallest_eigenpair(sxx, sxy, sxz, syy, syz, szz, ex, ey, ez, curv)) continue;
      // Towards the viewpoint (camera origin): (0 - p)·n ≥ 0.
      if (-(X[i] * ex + Y[i] * ey + Z[i] * ez) < 0.0) ex = -ex, ey = -ey, ez = -ez;
      NX[i] = float(ex);
      NY[i] = float(ey);
      NZ[i] = float(ez);
      CV[i] = float(curv);
    }
  }
}

void estimate_normals_integral(OrganizedCloud& cloud, const IntegralNormalConfig& cfg) {
  IntegralNormalEstimator est(cfg);
  est.compute(cloud);
}

}  // namespace cropsight::geometry
