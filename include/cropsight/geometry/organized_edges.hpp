#pragma once
// Organised depth-discontinuity edges (Choi, Trevor & Christensen, IROS 2013): the same rule as
// pcl::OrganizedEdgeBase, labels with PCL's bit values. For a valid pixel p (border rows and
// columns excluded) with all 8 neighbours valid: d = the neighbour depth difference |z_p| - |z_q|
// of largest magnitude; |d| > depth_discontinuity·|z_p| marks p OCCLUDED when d > 0 (p is behind
// its neighbour) and OCCLUDING when d < 0 (p is in front). With NaN neighbours, the search walks
// across the hole (mean direction of the NaN neighbours, up to max_search_neighbors pixels) to
// the first valid pixel and applies the same test; when none is found, p is a NAN_BOUNDARY.
//
// Optionally (ours, not PCL's rule): HIGH_CURVATURE (PCL's bit value 8) marks valid pixels whose
// surface variation (cloud.curvature, from the integral-image normals) exceeds
// high_curvature_threshold. PCL's OrganizedEdgeFromNormals finds such edges by Canny on the
// normals' x/y images; a threshold on the covariance curvature gives the same kind of barrier
// (creases where a head meets a leaf without a depth jump) at no extra cost, since the normal
// stage already computed it. Off when the threshold is <= 0 or the cloud has no normals.
#include <cstdint>
#include <vector>

#include "cropsight/core/organized_cloud.hpp"

namespace cropsight::geometry {

enum EdgeLabel : std::uint8_t {
  kEdgeNone = 0,
  kEdgeNanBoundary = 1,    ///< next to a hole with nothing found across it
  kEdgeOccluding = 2,      ///< the near side of a depth jump
  kEdgeOccluded = 4,       ///< the far side of a depth jump
  kEdgeHighCurvature = 8,  ///< crease: curvature above the threshold (optional, see above)
};

struct OrganizedEdgeConfig {
  float depth_discontinuity = 0.02f;  ///< relative: jump threshold = value · depth
  int max_search_neighbors = 50;      ///< pixels searched across NaN holes
  bool detect_nan_boundary = true;
  bool detect_occluding = true;
  bool detect_occluded = true;
  float high_curvature_threshold = 0.0f;  ///< surface variation; <= 0 disables (default)

  template <class V>
  void visit(V& v) {
    v("depth_discontinuity", depth_discontinuity,
      "relative depth jump (fraction of depth) that makes an edge (paper: 0.02, PCL OrganizedEdgeBase default, Choi et "
      "al. 2013)");
    v("max_search_neighbors", max_search_neighbors,
      "pixels searched across a NaN hole for the far side (paper: 50, PCL OrganizedEdgeBase default)");
    v("detect_nan_boundary", detect_nan_boundary, "label NaN-boundary edges (PCL default: true)");
    v("detect_occluding", detect_occluding, "label occluding edges (PCL default: true)");
    v("detect_occluded", detect_occluded, "label occluded edges (PCL default: true)");
    v("high_curvature_threshold", high_curvature_threshold,
      "surface variation above which a pixel is a HIGH_CURVATURE edge (ours; <= 0 disables; needs normals)");
  }
};

/// Fills `labels` (resized to width·height) with EdgeLabel values (one depth label per pixel,
/// plus the HIGH_CURVATURE bit when enabled); 0 = no edge.
/// Throws Error("organized edges", ...) for a bad config.
void detect_organized_edges(const OrganizedCloud& cloud, const OrganizedEdgeConfig& cfg,
                            std::vector<std::uint8_t>& labels);

inline std::vector<std::uint8_t> detect_organized_edges(const OrganizedCloud& cloud,
                                                        const OrganizedEdgeConfig& cfg = {}) {
  std::vector<std::uint8_t> labels;
  detect_organized_edges(cloud, cfg, labels);
  return labels;
}

}  // namespace cropsight::geometry
