#pragma once
// Statistical outlier removal (the FEC variant's pre-processing): the same rule as
// pcl::StatisticalOutlierRemoval. For each point, d = mean Euclidean distance to its k nearest
// neighbours (the point itself excluded); with μ and σ the mean and the sample standard deviation
// of d over all points, points with d > μ + std_mul·σ are removed. Neighbours are searched with a
// nanoflann k-d tree among the given points only.
#include <Eigen/Core>
#include <vector>

#include "cropsight/core/config.hpp"
#include "cropsight/core/organized_cloud.hpp"

namespace cropsight::geometry {

struct StatisticalOutlierConfig {
  int mean_k = 100;      ///< neighbours per point
  double std_mul = 1.0;  ///< threshold in standard deviations above the mean

  template <class V>
  void visit(V& v) {
    v("mean_k", mean_k, "neighbours used for the mean distance (paper: 100, Kusumam et al. 2017 §4.1)",
      Range::within(1, 10000));
    v("std_mul", std_mul, "outlier threshold: mean + std_mul * stddev (paper: 1.0, Kusumam et al. 2017 §4.1)",
      Range::within(0, 1e3));
  }
};

/// Kept subset of `indices` (pixel indices of valid points of `cloud`), in input order.
/// Throws Error("statistical outlier", ...) for mean_k < 1 or an index of an invalid point.
/// Fewer than 2 points: returned unchanged.
std::vector<int> remove_statistical_outliers(const OrganizedCloud& cloud, const std::vector<int>& indices,
                                             const StatisticalOutlierConfig& cfg);

/// Same on an unorganised point list: indices into `points` that are kept, ascending.
std::vector<int> remove_statistical_outliers(const std::vector<Eigen::Vector3f>& points,
                                             const StatisticalOutlierConfig& cfg);

}  // namespace cropsight::geometry
