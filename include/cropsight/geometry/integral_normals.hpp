#pragma once
// Integral-image normal estimation on an organised cloud, covariance-matrix method: the same
// algorithm as pcl::IntegralImageNormalEstimation with COVARIANCE_MATRIX, BORDER_POLICY_IGNORE
// and no depth-dependent smoothing, written here for speed (single pass over double-precision
// integral images of x, y, z and their second moments; no per-pixel allocation).
//
// For pixel (u, v) the normal is the eigenvector of the smallest eigenvalue λ0 of the covariance
// of the valid points in a square window of s×s pixels starting at (u - s/2, v - s/2), where
// s = int(min(normal_smoothing_size, D(u, v))) and D is the chamfer distance (1, 1.4) to the
// nearest "depth change" pixel (a pixel whose right or lower neighbour is NaN or differs in depth
// by more than max_depth_change_factor·(|z| + 1)·2 — PCL's rule). s ≤ 2, invalid points and a
// border of int(normal_smoothing_size) pixels give NaN. Normals point towards the viewpoint (the
// camera origin): n·(0 - p) ≥ 0. Curvature = λ0 / (λ0 + λ1 + λ2) (surface variation, in [0, 1/3]).
#include <cstdint>
#include <span>
#include <vector>

#include "cropsight/core/organized_cloud.hpp"

namespace cropsight::geometry {

struct IntegralNormalConfig {
  float max_depth_change_factor = 0.02f;  ///< dimensionless; PCL's depth-change factor
  float normal_smoothing_size = 10.0f;    ///< pixels; window side
  /// PCL's rule (true): a NaN neighbour is a depth change, so no window reaches within about
  /// two pixels of a hole. False: only two valid neighbours farther apart than the limit break a
  /// window; NaN pixels add nothing, and a window needs min_valid_fraction of its pixels valid.
  bool nan_breaks_window = true;
  float min_valid_fraction = 0.5f;  ///< of the s×s window's pixels; used when nan_breaks_window is false

  template <class V>
  void visit(V& v) {
    v("max_depth_change_factor", max_depth_change_factor,
      "depth-change factor: neighbours differing by more than factor*(|z|+1)*2 m break the window "
      "(paper: 0.02, PCL IntegralImageNormalEstimation as used by Montes et al. 2020)");
    v("normal_smoothing_size", normal_smoothing_size,
      "pixels; side of the averaging window (paper: 10, PCL IntegralImageNormalEstimation as used by Montes et al. "
      "2020)");
    v("nan_breaks_window", nan_breaks_window,
      "true: a NaN neighbour counts as a depth change (PCL's rule, paper); false: holes add nothing to the "
      "window, only valid neighbours that differ by more than the limit break it (ours, for ToF dropouts)");
    v("min_valid_fraction", min_valid_fraction,
      "fraction of the window's pixels that must be valid for a normal when nan_breaks_window is false (ours)");
  }
};

/// Reusable estimator: keeps its integral images between frames (no allocation once warm).
/// Not thread-safe; one per thread.
class IntegralNormalEstimator {
 public:
  explicit IntegralNormalEstimator(IntegralNormalConfig cfg = {});
  const IntegralNormalConfig& config() const { return cfg_; }

  /// Fills cloud.nx/ny/nz/curvature (allocated when absent; NaN where undefined).
  /// With a non-empty `select` (one int per pixel, e.g. segmentation::FloodFillWorkspace::labels),
  /// only pixels with select[i] >= 0 get a normal (the others stay NaN); each of them gets exactly
  /// the value the full computation gives (the depth-change and distance maps still cover the
  /// whole image). Throws Error("normals", ...) for a bad config (smoothing size < 1, negative
  /// factor) or a selection of another size.
  void compute(OrganizedCloud& cloud, std::span<const int> select = {});

 private:
  IntegralNormalConfig cfg_;
  std::vector<double> integral_;     // (w+1)·(h+1) cells × 10 sums: n, x, y, z, xx, xy, xz, yy, yz, zz
  std::vector<float> distance_;      // chamfer distance to the nearest depth change, pixels
  std::vector<float> scratch_;       // one row of the distance passes
  std::vector<std::uint8_t> flags_;  // per-row depth-change test results, then per-row "needs a normal" bytes
  std::vector<float> row_;           // per-row scatter matrices, positions, results (structure of arrays)
  std::vector<int> cols_;            // per-row: columns of the pixels that get a normal
  std::vector<int> sizes_;           // per-row: their window sizes
};

/// One-shot convenience wrapper (allocates its workspace).
void estimate_normals_integral(OrganizedCloud& cloud, const IntegralNormalConfig& cfg = {});

}  // namespace cropsight::geometry
