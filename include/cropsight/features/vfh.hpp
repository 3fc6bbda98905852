#pragma once
// Viewpoint Feature Histogram (Rusu et al., IROS 2010), the same computation as PCL 1.13's
// pcl::VFHEstimation (vfh.hpp) with its defaults, written here for speed (no PCL copies, no
// k-d tree). Layout of the 308 bins:
//   [0, 45)    f1 = atan2(w·n, u·n)        binned as floor(45·(f1 + π)/(2π))
//   [45, 90)   f2 = v·n (a cosine)         binned with the same formula as an angle (PCL's rule,
//   [90, 135)  f3 = u·d/|d| (a cosine)      so only the middle bins are used)
//   [135, 180) distance component: zeros unless size_component (PCL default false); then
//              floor(45·|d|/sqrt(max|d|² + 1)) with normalize_distances (PCL's 4-vector norm
//              again includes a w difference of 1), else round(100·|d|) (cm)
//   [180, 308) viewpoint component: floor(128·(n·v + 1)/2), v = -c / sqrt(|c|² + 1) for the
//              centroid c (camera at the origin). NOT a unit vector: PCL normalises the 4-vector
//              (viewpoint(w=0) - centroid(w=1)) = (-c, -1); we reproduce that quirk exactly
// where the pair (centroid c, mean normal n̄) → (point p, normal n) gives d = p - c and the
// Darboux frame u, v, w of PCL's computePairFeatures (source/target swapped when the target's
// normal is closer to parallel with d). With normalize_bins each f-bin adds 100/(N-1) and each
// viewpoint bin 100/N (N = points), so each f-histogram sums to 100·N/(N-1) and the viewpoint
// histogram to 100 — exactly PCL's normalisation.
#include <cstddef>
#include <span>
#include <vector>

#include "cropsight/core/organized_cloud.hpp"

namespace cropsight::features {

inline constexpr int kVfhBins = 308;

struct VfhConfig {
  bool normalize_bins = true;        ///< PCL default true
  bool normalize_distances = false;  ///< PCL default false
  bool size_component = false;       ///< PCL default false (distance bins stay zero)

  template <class V>
  void visit(V& v) {
    v("normalize_bins", normalize_bins, "scale bins by 100/points (PCL VFHEstimation default: true)");
    v("normalize_distances", normalize_distances,
      "distance bins relative to the largest distance (PCL default: false)");
    v("size_component", size_component, "fill the 45 distance bins (PCL default: false, bins stay zero)");
  }
};

/// VFH of the points `indices` of `cloud` (which must have normals). Points with a non-finite
/// position or normal are skipped (N counts the others). Writes kVfhBins floats to `out`; all
/// zeros when fewer than 2 usable points. Viewpoint: the camera origin.
void compute_vfh(const OrganizedCloud& cloud, std::span<const int> indices, const VfhConfig& cfg, float* out);

inline std::vector<float> compute_vfh(const OrganizedCloud& cloud, std::span<const int> indices,
                                      const VfhConfig& cfg = {}) {
  std::vector<float> h(kVfhBins);
  compute_vfh(cloud, indices, cfg, h.data());
  return h;
}

}  // namespace cropsight::features
