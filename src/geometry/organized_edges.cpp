// Organised depth-discontinuity edges, reproducing pcl::OrganizedEdgeBase::extractEdges (PCL 1.13)
// without its per-pixel std::vector: same neighbour order, same dominant-difference rule, same
// walk across NaN holes (mean direction of the NaN neighbours, floor() steps).
#include "cropsight/geometry/organized_edges.hpp"

#include <cmath>
#include <limits>

#include "cropsight/core/error.hpp"

namespace cropsight::geometry {

void detect_organized_edges(const OrganizedCloud& cloud, const OrganizedEdgeConfig& cfg,
                            std::vector<std::uint8_t>& labels) {
  if (!(cfg.depth_discontinuity >= 0.0f)) throw Error("organized edges", "depth_discontinuity must be >= 0");
  if (cfg.max_search_neighbors < 0) throw Error("organized edges", "max_search_neighbors must be >= 0");
  const int w = cloud.width, h = cloud.height;
  labels.assign(cloud.size(), kEdgeNone);
  const std::uint8_t occluded = cfg.detect_occluded ? kEdgeOccluded : 0;
  const std::uint8_t occluding = cfg.detect_occluding ? kEdgeOccluding : 0;
  const std::uint8_t nan_boundary = cfg.detect_nan_boundary ? kEdgeNanBoundary : 0;
  if (cfg.high_curvature_threshold > 0.0f && cloud.curvature.size() == cloud.size()) {
    const float* C = cloud.curvature.data();
    const float th = cfg.high_curvature_threshold;
    // NaN curvature compares false: pixels without a normal are not creases.
    for (std::size_t i = 0; i < cloud.size(); ++i)
      if (C[i] > th) labels[i] = kEdgeHighCurvature;
  }
  if ((occluded | occluding | nan_boundary) == 0) return;
  const float th = cfg.depth_discontinuity;
  const float* Z = cloud.z.data();
  // PCL's neighbour order: W, NW, N, NE, E, SE, S, SW.
  const int ddx[8] = {-1, -1, 0, 1, 1, 1, 0, -1};
  const int ddy[8] = {0, -1, -1, -1, 0, 1, 1, 1};
  int doff[8];
  for (int k = 0; k < 8; ++k) doff[k] = ddy[k] * w + ddx[k];

  for (int row = 1; row < h - 1; ++row) {
    for (int col = 1; col < w - 1; ++col) {
      const int i = row * w + col;
      const float zc = Z[i];
      if (!std::isfinite(zc)) continue;
      const float cur = std::abs(zc);
      float dmin = 0.0f, dmax = 0.0f;
      bool invalid = false;
      for (int k = 0; k < 8; ++k) {
        const float zn = Z[i + doff[k]];
        if (!std::isfinite(zn)) {
          invalid = true;
          break;
        }
        const float d = cur - std::abs(zn);
        if (k == 0 || d < dmin) dmin = d;
        if (k == 0 || d > dmax) dmax = d;
      }
      if (!invalid) {
        const float dominant = std::abs(dmin) > std::abs(dmax) ? dmin : dmax;
        if (std::abs(dominant) > th * cur) labels[i] |= dominant > 0.0f ? occluded : occluding;
        continue;
      }
      // Some neighbour is NaN: look across the hole along the mean direction of the NaN ones.
      int dx = 0, dy = 0, count = 0;
      for (int k = 0; k < 8; ++k) {
        if (!std::isfinite(Z[i + doff[k]])) {
          dx += ddx[k];
          dy += ddy[k];
          ++count;
        }
      }
      const float fdx = float(dx) / float(count), fdy = float(dy) / float(count);
      float corr = std::numeric_limits<float>::quiet_NaN();
      for (int s = 1; s < cfg.max_search_neighbors; ++s) {
        const int sr = row + int(std::floor(fdy * float(s)));
        const int sc = col + int(std::floor(fdx * float(s)));
        if (sr < 0 || sr >= h || sc < 0 || sc >= w) break;
        const float zs = Z[sr * w + sc];
        if (std::isfinite(zs)) {
          corr = std::abs(zs);
          break;
        }
      }
      if (!std::isnan(corr)) {
        const float d = cur - corr;
        if (std::abs(d) > th * cur) labels[i] |= d > 0.0f ? occluded : occluding;
      } else {
        labels[i] |= nan_boundary;
      }
    }
  }
}

}  // namespace cropsight::geometry
