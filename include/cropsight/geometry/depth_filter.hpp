#pragma once
// Depth-range filter on an organised cloud (pre-processing stage 1 of the broccoli pipelines).
#include <cstddef>
#include <vector>

#include "cropsight/core/config.hpp"
#include "cropsight/core/organized_cloud.hpp"

namespace cropsight::geometry {

struct DepthRangeConfig {
  float min_depth = 0.5f;  ///< m
  float max_depth = 1.0f;  ///< m

  template <class V>
  void visit(V& v) {
    // Ranges declared here so that check_config names the file the value came from.
    v("min_depth", min_depth, "m; points nearer than this become NaN (paper: 0.5 m, Kusumam et al. 2017 §4.1)",
      Range::at_least(0, "metres"));
    v("max_depth", max_depth, "m; points farther than this become NaN (paper: 1.0 m, Kusumam et al. 2017 §4.1)",
      Range::above(0, "metres"));
  }
  /// Throws Error("depth.min_depth" / "depth.max_depth" / "depth range", ...) unless
  /// 0 <= min_depth <= max_depth, both finite.
  void validate() const;
};

/// Sets x, y, z (and normals/curvature when present) to NaN where z is outside
/// [min_depth, max_depth] (inclusive) or not finite. The grid layout is unchanged.
/// Returns the number of valid points left. Throws Error("depth range", ...) when min > max.
std::size_t filter_depth_range(OrganizedCloud& cloud, const DepthRangeConfig& cfg);

/// Indices (row-major pixel index v*width+u) of the points with finite z, ascending.
std::vector<int> valid_indices(const OrganizedCloud& cloud);

}  // namespace cropsight::geometry
