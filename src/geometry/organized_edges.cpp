// Organised depth-discontinuity edges, reproducing pcl::OrganizedEdgeBase::extractEdges (PCL 1.13)
// without its per-pixel std::vector: same neighbour order, same dominant-difference rule, same
// walk across NaN holes (mean direction of the NaN neighbours, floor() steps).
#include "cropsight/geometry/organized_edges.hpp"

#include <cmath>
#include <cstring>
#include <limits>

#include "core/cpu_dispatch.hpp"
#include "cropsight/core/error.hpp"

namespace cropsight::geometry {

namespace {

constexpr std::uint8_t kSearch = 0x80;  // temporary mark: valid pixel with a NaN neighbour

// Exact floor for |f| < 2^31 without a libm call (baseline x86-64 has no roundss): truncate,
// then step down for negative non-integers. Same result as int(std::floor(f)).
inline int floor_int(float f) {
  const int t = int(f);
  return t - (f < float(t) ? 1 : 0);
}

// One image row (pixels 1..w-2 of `z`, neighbours at z ± stride): PCL's all-neighbours-valid
// rule, branch-free. dmin/dmax over the 8 differences |z_p| - |z_q|; the dominant one decides.
CROPSIGHT_AVX2_CLONES void row_fast_path(int w, const float* __restrict z, int stride, float th, std::uint8_t occluded,
                                         std::uint8_t occluding, std::uint8_t* __restrict out) {
  const float* up = z - stride;
  const float* dn = z + stride;
  out[0] = out[w - 1] = kEdgeNone;
  for (int c = 1; c < w - 1; ++c) {
    const float zc = z[c];
    const float cur = std::abs(zc);
    const float q[8] = {z[c - 1], up[c - 1], up[c], up[c + 1], z[c + 1], dn[c + 1], dn[c], dn[c - 1]};
    bool invalid = false;
    float dmin = cur - std::abs(q[0]), dmax = dmin;
    for (int k = 0; k < 8; ++k) {
      invalid |= !std::isfinite(q[k]);
      const float d = cur - std::abs(q[k]);
      dmin = std::min(dmin, d);
      dmax = std::max(dmax, d);
    }
    const float dominant = std::abs(dmin) > std::abs(dmax) ? dmin : dmax;
    const bool edge = std::abs(dominant) > th * cur;
    const std::uint8_t label = edge ? (dominant > 0.0f ? occluded : occluding) : std::uint8_t(kEdgeNone);
    const bool valid = std::isfinite(zc);
    out[c] = !valid ? std::uint8_t(kEdgeNone) : (invalid ? kSearch : label);
  }
}

// The same row when neither depth label is wanted (only NaN boundaries): marks the pixels with a
// NaN neighbour for the walk, leaves the others unlabelled, without the eight depth differences.
CROPSIGHT_AVX2_CLONES void row_nan_only(int w, const float* __restrict z, int stride, std::uint8_t* __restrict out) {
  const float* up = z - stride;
  const float* dn = z + stride;
  out[0] = out[w - 1] = kEdgeNone;
  for (int c = 1; c < w - 1; ++c) {
    const float q[8] = {z[c - 1], up[c - 1], up[c], up[c + 1], z[c + 1], dn[c + 1], dn[c], dn[c - 1]};
    bool invalid = false;
    for (int k = 0; k < 8; ++k) invalid |= !std::isfinite(q[k]);
    out[c] = std::isfinite(z[c]) && invalid ? kSearch : std::uint8_t(kEdgeNone);
  }
}

}  // namespace

// Long on purpose: a hot loop over the image with PCL's neighbour tests inlined per pixel.
void detect_organized_edges(const OrganizedCloud& cloud, const OrganizedEdgeConfig& cfg,
                            std::vector<std::uint8_t>& labels) {
  if (!(cfg.depth_discontinuity >= 0.0f)) throw Error("organized edges", "depth_discontinuity must be >= 0");
  if (cfg.max_search_neighbors < 0) throw Error("organized edges", "max_search_neighbors must be >= 0");
  const int w = cloud.width, h = cloud.height;
  labels.assign(cloud.size(), kEdgeNone);
  const std::uint8_t occluded = cfg.detect_occluded ? kEdgeOccluded : 0;
  const std::uint8_t occluding = cfg.detect_occluding ? kEdgeOccluding : 0;
  const std::uint8_t nan_boundary = cfg.detect_nan_boundary ? kEdgeNanBoundary : 0;
  const bool curvature_bits = cfg.high_curvature_threshold > 0.0f && cloud.curvature.size() == cloud.size();
  if ((occluded | occluding | nan_boundary) == 0) {
    if (curvature_bits)
      for (std::size_t i = 0; i < cloud.size(); ++i)
        if (cloud.curvature[i] > cfg.high_curvature_threshold) labels[i] = kEdgeHighCurvature;
    return;
  }
  const float th = cfg.depth_discontinuity;
  const float* Z = cloud.z.data();
  // PCL's neighbour order: W, NW, N, NE, E, SE, S, SW.
  const int ddx[8] = {-1, -1, 0, 1, 1, 1, 0, -1};
  const int ddy[8] = {0, -1, -1, -1, 0, 1, 1, 1};
  int doff[8];
  for (int k = 0; k < 8; ++k) doff[k] = ddy[k] * w + ddx[k];
  // Walk steps per direction (dx, dy in -8..8, count 1..8 → 17·17·9 keys), filled on first use:
  // each step's row and column offset and its offset in the flat image.
  struct Step {
    int dr, dc, offset;
  };
  std::vector<int> dir_slot(17 * 17 * 9, -1);
  std::vector<Step> steps;

  for (int row = 1; row < h - 1; ++row) {
    std::uint8_t* lrow = labels.data() + std::size_t(row) * w;
    // Fast path for the whole row (branch-free, vectorised): pixels whose 8 neighbours are all
    // valid get their label (none when no depth label is wanted); pixels with a NaN neighbour are
    // marked kSearch for the walk below.
    if (occluded | occluding)
      row_fast_path(w, Z + std::size_t(row) * w, w, th, occluded, occluding, lrow);
    else
      row_nan_only(w, Z + std::size_t(row) * w, w, lrow);
    // The marked pixels are few: memchr finds them (the walk below writes only lrow[col]).
    for (std::uint8_t* p = lrow + 1; p < lrow + w - 1; ++p) {
      p = static_cast<std::uint8_t*>(std::memchr(p, kSearch, std::size_t(lrow + w - 1 - p)));
      if (!p) break;
      const int col = int(p - lrow);
      const int i = row * w + col;
      const float cur = std::abs(Z[i]);
      // Some neighbour is NaN: look across the hole along the mean direction of the NaN ones.
      int dx = 0, dy = 0, count = 0;
      for (int k = 0; k < 8; ++k) {
        if (!std::isfinite(Z[i + doff[k]])) {
          dx += ddx[k];
          dy += ddy[k];
          ++count;
        }
      }
      // The walk's steps depend only on (dx, dy, count): computed once per direction and frame
      // with PCL's float expressions, then reused (a table lookup per step instead of two float
      // multiplies and floors).
      const int key = ((dx + 8) * 17 + (dy + 8)) * 9 + count;
      int& slot = dir_slot[std::size_t(key)];
      if (slot < 0) {
        slot = int(steps.size());
        const float fdx = float(dx) / float(count), fdy = float(dy) / float(count);
        for (int s = 1; s < cfg.max_search_neighbors; ++s) {
          const int dr = floor_int(fdy * float(s)), dc = floor_int(fdx * float(s));
          steps.push_back({dr, dc, dr * w + dc});
        }
      }
      const Step* st = steps.data() + slot;
      float corr = std::numeric_limits<float>::quiet_NaN();
      for (int s = 1; s < cfg.max_search_neighbors; ++s) {
        // Inside the image: one unsigned comparison per coordinate (a negative one wraps high).
        const Step& step = st[s - 1];
        if (unsigned(row + step.dr) >= unsigned(h) || unsigned(col + step.dc) >= unsigned(w)) break;
        const float zs = Z[i + step.offset];
        if (std::isfinite(zs)) {
          corr = std::abs(zs);
          break;
        }
      }
      std::uint8_t l = kEdgeNone;
      if (!std::isnan(corr)) {
        const float d = cur - corr;
        if (std::abs(d) > th * cur) l = d > 0.0f ? occluded : occluding;
      } else {
        l = nan_boundary;
      }
      lrow[col] = l;
    }
  }
  if (curvature_bits) {
    const float* C = cloud.curvature.data();
    const float tc = cfg.high_curvature_threshold;
    // NaN curvature compares false: pixels without a normal are not creases.
    for (std::size_t i = 0; i < cloud.size(); ++i)
      if (C[i] > tc) labels[i] |= kEdgeHighCurvature;
  }
}

}  // namespace cropsight::geometry
