#pragma once
// Euclidean cluster extraction (the FEC baseline of Montes et al. 2020): the same rule as
// pcl::EuclideanClusterExtraction — connected components of the graph linking points closer than
// `tolerance` — on an unorganised index set, with a nanoflann k-d tree. Clusters outside
// [min_size, max_size] are dropped (not split). Output order: by smallest member index
// (deterministic); indices within a segment ascending.
#include <memory>
#include <vector>

#include "cropsight/core/organized_cloud.hpp"
#include "cropsight/core/segment.hpp"

namespace cropsight::segmentation {

struct EuclideanClusterConfig {
  float tolerance = 0.005f;  ///< m
  int min_size = 500;        ///< points
  int max_size = 10000;      ///< points

  template <class V>
  void visit(V& v) {
    v("tolerance", tolerance,
      "m; neighbour distance that links points (paper: 0.005 UK, 0.004 Spain; Montes et al. 2020)");
    v("min_size", min_size, "points; smaller clusters are dropped (paper: 500 UK, 300 Spain)");
    v("max_size", max_size, "points; larger clusters are dropped (paper: 10000)");
  }
};

/// Euclidean clustering of `indices` (valid points of `cloud`); returned segments index `cloud`
/// and are summarize()d. Throws Error("euclidean clustering", ...) for a bad config or an index
/// of an invalid point.
std::vector<Segment> euclidean_clusters(const OrganizedCloud& cloud, const std::vector<int>& indices,
                                        const EuclideanClusterConfig& cfg);

/// Same on a plain point list; segment indices index `points`, summaries left empty.
std::vector<Segment> euclidean_clusters(const std::vector<Eigen::Vector3f>& points, const EuclideanClusterConfig& cfg);

}  // namespace cropsight::segmentation
