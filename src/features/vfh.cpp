// VFH, reproducing pcl::VFHEstimation::computeFeature and pcl::computePairFeatures (PCL 1.13)
// in one pass over the segment, without copying it into PCL point clouds. Float arithmetic is
// kept where PCL uses float so that the bins agree; the one deliberate change is the pair
// "swap" test: PCL compares acos(|a1|) > acos(|a2|), which for |a| ≤ 1 is |a1| < |a2| (acos is
// decreasing), evaluated here without the two acos calls.
#include "cropsight/features/vfh.hpp"

#include <algorithm>
#include <cmath>

namespace cropsight::features {

namespace {
inline bool usable(const OrganizedCloud& c, int i) {
  return std::isfinite(c.x[i]) && std::isfinite(c.y[i]) && std::isfinite(c.z[i]) && std::isfinite(c.nx[i]) &&
         std::isfinite(c.ny[i]) && std::isfinite(c.nz[i]);
}
}  // namespace

void compute_vfh(const OrganizedCloud& cloud, std::span<const int> indices, const VfhConfig& cfg, float* out) {
  std::fill(out, out + kVfhBins, 0.0f);
  if (!cloud.has_normals()) return;
  // Step 1: centroid (position) and mean normal (not renormalised, as in PCL).
  double sx = 0, sy = 0, sz = 0;
  float snx = 0, sny = 0, snz = 0;
  std::size_t n = 0;
  for (int i : indices) {
    if (!usable(cloud, i)) continue;
    sx += cloud.x[i], sy += cloud.y[i], sz += cloud.z[i];
    snx += cloud.nx[i], sny += cloud.ny[i], snz += cloud.nz[i];
    ++n;
  }
  if (n < 2) return;
  const float cx = float(sx / double(n)), cy = float(sy / double(n)), cz = float(sz / double(n));
  const float fn = float(n);
  const float n1x = snx / fn, n1y = sny / fn, n1z = snz / fn;

  // Distance normalisation (only used with size_component && normalize_distances).
  float max_dist = 1.0f;
  if (cfg.size_component && cfg.normalize_distances) {
    float best = -1.0f;
    for (int i : indices) {
      if (!usable(cloud, i)) continue;
      const float dx = cloud.x[i] - cx, dy = cloud.y[i] - cy, dz = cloud.z[i] - cz;
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

  const float f_incr = cfg.normalize_bins ? 100.0f / float(n - 1) : 1.0f;
  const float vp_incr = cfg.normalize_bins ? float(100.0 / double(n)) : 1.0f;
  const double d_pi = double(1.0f / (2.0f * float(M_PI)));
  float* h1 = out;
  float* h2 = out + 45;
  float* h3 = out + 90;
  float* h4 = out + 135;
  float* hvp = out + 180;
  auto angle_bin = [&](float f) {
    const int raw = int(std::floor(45.0 * ((double(f) + M_PI) * d_pi)));
    return std::clamp(raw, 0, 44);
  };

  for (int i : indices) {
    if (!usable(cloud, i)) continue;
    const float px = cloud.x[i], py = cloud.y[i], pz = cloud.z[i];
    const float n2x = cloud.nx[i], n2y = cloud.ny[i], n2z = cloud.nz[i];

    // Viewpoint component (every usable point, including those with no pair feature).
    {
      const double alpha = (double(n2x * vx + n2y * vy + n2z * vz) + 1.0) * 0.5;
      const int fi = std::clamp(int(std::floor(alpha * 128.0)), 0, 127);
      hvp[fi] += vp_incr;
    }

    // Pair features (centroid, mean normal) → (point, normal), pcl::computePairFeatures.
    float dx = px - cx, dy = py - cy, dz = pz - cz;
    const float f4 = std::sqrt(dx * dx + dy * dy + dz * dz);
    if (f4 == 0.0f) continue;
    const float a1 = (n1x * dx + n1y * dy + n1z * dz) / f4;
    const float a2 = (n2x * dx + n2y * dy + n2z * dz) / f4;
    const float fa1 = std::fabs(a1), fa2 = std::fabs(a2);
    float ux = n1x, uy = n1y, uz = n1z;  // source normal
    float tx = n2x, ty = n2y, tz = n2z;  // target normal
    float f3;
    if (fa1 < fa2 && fa1 <= 1.0f && fa2 <= 1.0f) {  // ⇔ acos(|a1|) > acos(|a2|)
      std::swap(ux, tx), std::swap(uy, ty), std::swap(uz, tz);
      dx = -dx, dy = -dy, dz = -dz;
      f3 = -a2;
    } else {
      f3 = a1;
    }
    // v = d × u, normalised; w = u × v.
    float wx0 = dy * uz - dz * uy, wy0 = dz * ux - dx * uz, wz0 = dx * uy - dy * ux;
    const float vnorm = std::sqrt(wx0 * wx0 + wy0 * wy0 + wz0 * wz0);
    if (vnorm == 0.0f) continue;
    const float vvx = wx0 / vnorm, vvy = wy0 / vnorm, vvz = wz0 / vnorm;
    const float wx = uy * vvz - uz * vvy, wy = uz * vvx - ux * vvz, wz = ux * vvy - uy * vvx;
    const float f2 = vvx * tx + vvy * ty + vvz * tz;
    const float f1 = std::atan2(wx * tx + wy * ty + wz * tz, ux * tx + uy * ty + uz * tz);

    h1[angle_bin(f1)] += f_incr;
    h2[angle_bin(f2)] += f_incr;
    h3[angle_bin(f3)] += f_incr;
    if (cfg.size_component) {
      const int hi = cfg.normalize_distances ? int(std::floor(45.0 * (double(f4) / double(max_dist))))
                                             : int(std::floor(double(f4) * 100.0 + 0.5));  // pcl_round
      h4[std::clamp(hi, 0, 44)] += f_incr;
    }
  }
}

}  // namespace cropsight::features
