// VFH, reproducing pcl::VFHEstimation::computeFeature and pcl::computePairFeatures (PCL 1.13)
// without copying the segment into PCL point clouds. Float arithmetic is kept where PCL uses
// float so that the bins agree; the one deliberate change is the pair "swap" test: PCL compares
// acos(|a1|) > acos(|a2|), which for |a| ≤ 1 is |a1| < |a2| (acos is decreasing), evaluated here
// without the two acos calls.
//
// For speed the usable points are gathered once into structure-of-arrays buffers (the centroid
// sums then run over them), their bins computed in blocks by one branch-free loop that the
// compiler vectorises (AVX2 / AVX-512 clone picked at run time; no FMA, so every float operation
// rounds as in the scalar code), and the bins counted as integers: every point adds the same
// increment to its bin, so a bin's float sum after c additions is the c-th entry of the running
// sum 0, inc, inc + inc, ... (the same float additions as a point-by-point loop). atan2 is
// the only call that does not vectorise: the loop uses a polynomial atan2 (Cephes atanf, error
// ~1e-7 rad) and only points whose angle lies within 1e-4 of a bin boundary (far more than the
// polynomial's error) are recomputed with std::atan2, so every bin is the one std::atan2 gives.
#include "cropsight/features/vfh.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "core/cpu_dispatch.hpp"

namespace cropsight::features {

namespace {

constexpr int kBlock = 256;  // points per block (stack buffers: ~17 KB)

// The usable points of one segment, structure of arrays (x, y, z, nx, ny, nz planes of `n`).
struct Points {
  const float *x, *y, *z, *nx, *ny, *nz;
};

// The per-point results of one block.
struct Block {
  alignas(32) int vp[kBlock], b1[kBlock], b2[kBlock], b3[kBlock], flag[kBlock];
  alignas(32) float f4[kBlock], f1y[kBlock], f1x[kBlock];
};

// Frame constants of one segment.
struct Frame {
  float cx, cy, cz;     // centroid
  float n1x, n1y, n1z;  // mean normal
  float vx, vy, vz;     // PCL's view direction
};

// flag bits: 1 = the pair feature exists (f4 != 0 and |d × u| != 0), 2 = f1's bin needs std::atan2.
constexpr int kPair = 1, kExactF1 = 2;

// Bin of an angle-like value f in [-π, π] → floor(45·(f + π)/(2π)), PCL's formula in double.
inline int angle_bin(float f, double d_pi) {
  const double t = 45.0 * ((double(f) + M_PI) * d_pi);
  const int raw = int(std::floor(t));
  return raw < 0 ? 0 : (raw > 44 ? 44 : raw);
}

// atan2(y, x) from Cephes' atanf polynomial on [0, tan(π/8)] with the usual reductions; error a
// few 1e-7 rad. Branch-free (selects) so that the block loop vectorises.
inline float atan2_poly(float y, float x) {
  const float ax = std::fabs(x), ay = std::fabs(y);
  const float mx = ax > ay ? ax : ay, mn = ax > ay ? ay : ax;
  const float a = mn / (mx > 0.0f ? mx : 1.0f);  // in [0, 1]
  const bool big = a > 0.41421356f;              // tan(π/8)
  const float r = big ? (a - 1.0f) / (a + 1.0f) : a;
  const float zz = r * r;
  float t =
      (((8.05374449538e-2f * zz - 1.38776856032e-1f) * zz + 1.99777106478e-1f) * zz - 3.33329491539e-1f) * zz * r + r;
  t = big ? t + 0.78539816f : t;
  t = ay > ax ? 1.57079633f - t : t;
  t = x < 0.0f ? 3.14159265f - t : t;
  return y < 0.0f ? -t : t;
}

// Bins of one block (n ≤ kBlock points). The float expressions are those of the scalar
// computePairFeatures port, in the same order.
CROPSIGHT_AVX2_CLONES void block_bins(int n, const Points& p, Block& b, const Frame& f, double d_pi) {
  for (int k = 0; k < n; ++k) {
    const float px = p.x[k], py = p.y[k], pz = p.z[k];
    const float n2x = p.nx[k], n2y = p.ny[k], n2z = p.nz[k];
    // Viewpoint component.
    const double alpha = (double(n2x * f.vx + n2y * f.vy + n2z * f.vz) + 1.0) * 0.5;
    const int fi = int(std::floor(alpha * 128.0));
    b.vp[k] = fi < 0 ? 0 : (fi > 127 ? 127 : fi);
    // Pair features (centroid, mean normal) → (point, normal).
    float dx = px - f.cx, dy = py - f.cy, dz = pz - f.cz;
    const float f4 = std::sqrt(dx * dx + dy * dy + dz * dz);
    const float sf4 = f4 != 0.0f ? f4 : 1.0f;
    const float a1 = (f.n1x * dx + f.n1y * dy + f.n1z * dz) / sf4;
    const float a2 = (n2x * dx + n2y * dy + n2z * dz) / sf4;
    const float fa1 = std::fabs(a1), fa2 = std::fabs(a2);
    const bool swap = fa1 < fa2 && fa1 <= 1.0f && fa2 <= 1.0f;  // ⇔ acos(|a1|) > acos(|a2|)
    const float ux = swap ? n2x : f.n1x, uy = swap ? n2y : f.n1y, uz = swap ? n2z : f.n1z;
    const float tx = swap ? f.n1x : n2x, ty = swap ? f.n1y : n2y, tz = swap ? f.n1z : n2z;
    dx = swap ? -dx : dx, dy = swap ? -dy : dy, dz = swap ? -dz : dz;
    const float f3 = swap ? -a2 : a1;
    // v = d × u, normalised; w = u × v.
    const float wx0 = dy * uz - dz * uy, wy0 = dz * ux - dx * uz, wz0 = dx * uy - dy * ux;
    const float vnorm = std::sqrt(wx0 * wx0 + wy0 * wy0 + wz0 * wz0);
    const float sv = vnorm != 0.0f ? vnorm : 1.0f;
    const float vvx = wx0 / sv, vvy = wy0 / sv, vvz = wz0 / sv;
    const float wx = uy * vvz - uz * vvy, wy = uz * vvx - ux * vvz, wz = ux * vvy - uy * vvx;
    const float f2 = vvx * tx + vvy * ty + vvz * tz;
    const float ay = wx * tx + wy * ty + wz * tz, ax = ux * tx + uy * ty + uz * tz;
    const float f1 = atan2_poly(ay, ax);
    // Near a bin boundary (or at the origin, where atan2's sign conventions matter) the bin is
    // recomputed with std::atan2 by the caller.
    const double t1 = 45.0 * ((double(f1) + M_PI) * d_pi);
    const double frac = t1 - std::floor(t1);
    const bool exact = frac < 1e-4 || frac > 1.0 - 1e-4 || !(std::fabs(ax) + std::fabs(ay) > 1e-30f);
    b.b1[k] = angle_bin(f1, d_pi);
    b.b2[k] = angle_bin(f2, d_pi);
    b.b3[k] = angle_bin(f3, d_pi);
    b.f4[k] = f4;
    b.f1y[k] = ay, b.f1x[k] = ax;
    b.flag[k] = ((f4 != 0.0f) & (vnorm != 0.0f) ? kPair : 0) | (exact ? kExactF1 : 0);
  }
}

// The usable points of `indices` (finite position and normal), in index order, as planes of
// `buf` (6 planes of indices.size() floats); returns their count.
std::size_t gather_usable(const OrganizedCloud& c, std::span<const int> indices, std::unique_ptr<float[]>& buf,
                          Points& p) {
  const std::size_t cap = indices.size();
  buf = std::make_unique_for_overwrite<float[]>(6 * cap);  // not zeroed: every read entry is written first
  float* x = buf.get();
  float *y = x + cap, *z = y + cap, *nx = z + cap, *ny = nx + cap, *nz = ny + cap;
  const float *X = c.x.data(), *Y = c.y.data(), *Z = c.z.data();
  const float *NX = c.nx.data(), *NY = c.ny.data(), *NZ = c.nz.data();
  std::size_t m = 0;
  for (int i : indices) {
    // Usable: finite position and normal. Written unconditionally, kept by advancing m: no
    // branch on the (unpredictable) test.
    const float a = X[i], b = Y[i], d = Z[i], e = NX[i], f = NY[i], g = NZ[i];
    x[m] = a, y[m] = b, z[m] = d, nx[m] = e, ny[m] = f, nz[m] = g;
    const bool ok =
        std::isfinite(a) & std::isfinite(b) & std::isfinite(d) & std::isfinite(e) & std::isfinite(f) & std::isfinite(g);
    m += ok ? 1 : 0;
  }
  p = Points{x, y, z, nx, ny, nz};
  return m;
}

// hist[b] = the float sum of count[b] additions of `inc` to 0, as a point-by-point loop adds
// them: the running sums 0, inc, inc + inc, ... up to the largest count.
void counts_to_bins(const int* count, int bins, float inc, std::vector<float>& sums, float* hist) {
  const int most = *std::max_element(count, count + bins);
  sums.resize(std::size_t(most) + 1);
  float s = 0.0f;
  sums[0] = s;
  for (int c = 1; c <= most; ++c) sums[std::size_t(c)] = s = s + inc;
  for (int b = 0; b < bins; ++b) hist[b] = sums[std::size_t(count[b])];
}
}  // namespace

// Long on purpose: PCL's VFH as its numbered steps in one hot pass per cluster.
void compute_vfh(const OrganizedCloud& cloud, std::span<const int> indices, const VfhConfig& cfg, float* out) {
  std::fill(out, out + kVfhBins, 0.0f);
  if (!cloud.has_normals()) return;
  std::unique_ptr<float[]> buf;
  Points p;
  const std::size_t n = gather_usable(cloud, indices, buf, p);
  if (n < 2) return;
  // Step 1: centroid (position) and mean normal (not renormalised, as in PCL).
  double sx = 0, sy = 0, sz = 0;
  float snx = 0, sny = 0, snz = 0;
  for (std::size_t k = 0; k < n; ++k) {
    sx += p.x[k], sy += p.y[k], sz += p.z[k];
    snx += p.nx[k], sny += p.ny[k], snz += p.nz[k];
  }
  const float cx = float(sx / double(n)), cy = float(sy / double(n)), cz = float(sz / double(n));
  const float fn = float(n);
  const float n1x = snx / fn, n1y = sny / fn, n1z = snz / fn;

  // Distance normalisation (only used with size_component && normalize_distances).
  float max_dist = 1.0f;
  if (cfg.size_component && cfg.normalize_distances) {
    float best = -1.0f;
    for (std::size_t k = 0; k < n; ++k) {
      const float dx = p.x[k] - cx, dy = p.y[k] - cy, dz = p.z[k] - cz;
      best = std::max(best, dx * dx + dy * dy + dz * dz);
    }
    // PCL: (centroid(w=1) - farthest(w=0)).norm() — the w difference of 1 is included.
    max_dist = std::sqrt(best + 1.0f);
  }

  // View direction, exactly as PCL computes it: d = viewpoint - centroid with 4-vectors, where
  // the viewpoint has w = 0 and the centroid (compute3DCentroid) w = 1, so d = (-c, -1) and its
  // normalisation divides by sqrt(|c|² + 1), not |c|. The 3D part is therefore shorter than a
  // unit vector, by |c| / sqrt(|c|² + 1) (0.63 at 0.8 m). Kept for bin-exact agreement.
  float vx = -cx, vy = -cy, vz = -cz;
  {
    const float len = std::sqrt(vx * vx + vy * vy + vz * vz + 1.0f);
    vx /= len, vy /= len, vz /= len;
  }
  const Frame frame{cx, cy, cz, n1x, n1y, n1z, vx, vy, vz};

  const float f_incr = cfg.normalize_bins ? 100.0f / float(n - 1) : 1.0f;
  const float vp_incr = cfg.normalize_bins ? float(100.0 / double(n)) : 1.0f;
  const double d_pi = double(1.0f / (2.0f * float(M_PI)));

  // Step 2: blocks of usable points → bins (vectorised) → integer counts per bin, in the
  // histogram's layout (f1 45, f2 45, f3 45, f4 45, viewpoint 128).
  int count[kVfhBins] = {};
  int* c1 = count;
  int* c2 = count + 45;
  int* c3 = count + 90;
  int* c4 = count + 135;
  int* cvp = count + 180;
  Block b;
  for (std::size_t first = 0; first < n; first += kBlock) {
    const int m = int(std::min<std::size_t>(kBlock, n - first));
    const Points q{p.x + first, p.y + first, p.z + first, p.nx + first, p.ny + first, p.nz + first};
    block_bins(m, q, b, frame, d_pi);
    for (int k = 0; k < m; ++k) {
      ++cvp[b.vp[k]];  // every usable point, including those with no pair feature
      const int flag = b.flag[k];
      if (!(flag & kPair)) continue;
      const int bin1 = (flag & kExactF1) ? angle_bin(std::atan2(b.f1y[k], b.f1x[k]), d_pi) : b.b1[k];
      ++c1[bin1];
      ++c2[b.b2[k]];
      ++c3[b.b3[k]];
      if (cfg.size_component) {
        const float f4 = b.f4[k];
        const int hi = cfg.normalize_distances ? int(std::floor(45.0 * (double(f4) / double(max_dist))))
                                               : int(std::floor(double(f4) * 100.0 + 0.5));  // pcl_round
        ++c4[std::clamp(hi, 0, 44)];
      }
    }
  }
  std::vector<float> sums;
  counts_to_bins(count, 180, f_incr, sums, out);
  counts_to_bins(cvp, 128, vp_incr, sums, out + 180);
}

}  // namespace cropsight::features
