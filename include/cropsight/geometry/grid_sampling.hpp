#pragma once
// Non-uniform grid down-sampling (the seedling paper's step before the GMM): the bounding box of
// the cloud is split recursively into octants until each box holds at most `max_points_per_box`
// points (or is smaller than `min_box_size`); each box then contributes one representative, the
// point closest to the box's centroid. Dense regions keep more points than a uniform voxel grid
// would, sparse ones fewer. sample_exact() then draws exactly `target_points` of them.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "cropsight/core/config.hpp"

namespace cropsight::geometry {

/// Largest target_points accepted (the paper uses 4096).
inline constexpr int kMaxGridTargetPoints = 1 << 20;

struct GridSamplingConfig {
  int target_points = 4096;    ///< points after sampling (paper: 4096)
  int max_points_per_box = 0;  ///< split threshold; 0 = floor(N / target_points), so boxes >= target
  double min_box_size = 1e-4;  ///< m; boxes smaller than this are not split further
  std::uint32_t seed = 1;      ///< choice among the representatives when there are more than the target

  template <class V>
  void visit(V& v) {
    v("target_points", target_points, "points kept after down-sampling (paper: 4096)",
      Range::within(1, kMaxGridTargetPoints));
    v("max_points_per_box", max_points_per_box, "boxes with more points are split; 0 = N / target_points",
      Range::within(0, 1 << 30));
    v("min_box_size", min_box_size, "m; smallest box side that is still split", Range::within(1e-9, 1e3));
    v("seed", seed, "random seed of the final draw");
  }
};

/// Representatives (indices into `points`, ascending) of the recursive split with the given
/// threshold. Non-finite points are skipped. Throws Error("grid sampling", ...) when
/// max_points_per_box < 1 or min_box_size <= 0.
std::vector<int> nonuniform_grid_representatives(const std::vector<Eigen::Vector3f>& points, int max_points_per_box,
                                                 double min_box_size);

/// Exactly cfg.target_points indices into `points` (ascending unless padded): the
/// representatives of the split, reduced by a seeded random draw when there are more. A cloud
/// with fewer finite points than the target is returned whole and padded by repeating points in
/// order (so the count is always exact). Throws Error("grid sampling", ...) when the cloud has
/// no finite point or target_points < 1.
std::vector<int> sample_exact(const std::vector<Eigen::Vector3f>& points, const GridSamplingConfig& cfg);

}  // namespace cropsight::geometry
