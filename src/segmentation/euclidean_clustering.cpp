// Euclidean cluster extraction with a nanoflann k-d tree, the rule of
// pcl::extractEuclideanClusters: breadth-first growth over radius neighbourhoods. The radius
// search feeds a result set that marks and enqueues unprocessed neighbours directly, so no
// neighbour list is allocated per query.
#include "cropsight/segmentation/euclidean_clustering.hpp"

#include <algorithm>
#include <cmath>

#include "cropsight/core/error.hpp"
#include "geometry/point_kdtree.hpp"

namespace cropsight::segmentation {

namespace {

using geometry::detail::PackedPoints;
using geometry::detail::PointKdTree;

// nanoflann result-set interface: every point within the radius that is not processed yet is
// marked and appended to the BFS queue.
struct GrowResultSet {
  float radius2;
  std::vector<unsigned char>& processed;
  std::vector<int>& queue;
  std::size_t found = 0;

  void init() {}
  std::size_t size() const { return found; }
  bool full() const { return true; }
  float worstDist() const { return radius2; }
  bool addPoint(float dist, std::uint32_t index) {
    if (dist < radius2 && !processed[index]) {
      processed[index] = 1;
      queue.push_back(int(index));
      ++found;
    }
    return true;
  }
};

std::vector<std::vector<int>> cluster_packed(const PackedPoints& pts, const EuclideanClusterConfig& cfg) {
  if (!(cfg.tolerance > 0.0f)) throw Error("euclidean clustering", "tolerance must be > 0");
  if (cfg.min_size < 1 || cfg.max_size < cfg.min_size)
    throw Error("euclidean clustering", "size range must satisfy 1 <= min_size <= max_size");
  const std::size_t n = pts.kdtree_get_point_count();
  std::vector<std::vector<int>> clusters;
  if (n == 0) return clusters;
  PointKdTree tree(3, pts, geometry::detail::kdtree_params());
  tree.buildIndex();
  std::vector<unsigned char> processed(n, 0);
  std::vector<int> queue;
  queue.reserve(n);
  const nanoflann::SearchParams params(32, 0.0f, false);
  for (std::size_t i = 0; i < n; ++i) {
    if (processed[i]) continue;
    queue.clear();
    queue.push_back(int(i));
    processed[i] = 1;
    for (std::size_t q = 0; q < queue.size(); ++q) {
      GrowResultSet rs{cfg.tolerance * cfg.tolerance, processed, queue};
      tree.findNeighbors(rs, &pts.xyz[3 * std::size_t(queue[q])], params);
    }
    const int size = int(queue.size());
    if (size >= cfg.min_size && size <= cfg.max_size) {
      clusters.emplace_back(queue.begin(), queue.end());
      std::sort(clusters.back().begin(), clusters.back().end());
    }
  }
  return clusters;
}

}  // namespace

std::vector<Segment> euclidean_clusters(const OrganizedCloud& cloud, const std::vector<int>& indices,
                                        const EuclideanClusterConfig& cfg) {
  PackedPoints pts;
  pts.xyz.resize(indices.size() * 3);
  for (std::size_t j = 0; j < indices.size(); ++j) {
    const int i = indices[j];
    if (i < 0 || std::size_t(i) >= cloud.size() || !cloud.valid(std::size_t(i)))
      throw Error("euclidean clustering", "index " + std::to_string(i) + " is not a valid point of the cloud");
    pts.xyz[3 * j] = cloud.x[i];
    pts.xyz[3 * j + 1] = cloud.y[i];
    pts.xyz[3 * j + 2] = cloud.z[i];
  }
  auto clusters = cluster_packed(pts, cfg);
  std::vector<Segment> out(clusters.size());
  for (std::size_t c = 0; c < clusters.size(); ++c) {
    out[c].indices.reserve(clusters[c].size());
    for (int k : clusters[c]) out[c].indices.push_back(indices[std::size_t(k)]);
    // Ascending pixel order when the input indices were ascending (the usual valid_indices()).
    std::sort(out[c].indices.begin(), out[c].indices.end());
    summarize(out[c], cloud);
  }
  // Order by smallest member (pixel) index, independent of the input order.
  std::sort(out.begin(), out.end(), [](const Segment& a, const Segment& b) { return a.indices[0] < b.indices[0]; });
  return out;
}

std::vector<Segment> euclidean_clusters(const std::vector<Eigen::Vector3f>& points, const EuclideanClusterConfig& cfg) {
  PackedPoints pts;
  pts.xyz.resize(points.size() * 3);
  for (std::size_t j = 0; j < points.size(); ++j) {
    if (!points[j].allFinite()) throw Error("euclidean clustering", "point " + std::to_string(j) + " is not finite");
    pts.xyz[3 * j] = points[j].x();
    pts.xyz[3 * j + 1] = points[j].y();
    pts.xyz[3 * j + 2] = points[j].z();
  }
  auto clusters = cluster_packed(pts, cfg);
  std::vector<Segment> out(clusters.size());
  for (std::size_t c = 0; c < clusters.size(); ++c) out[c].indices = std::move(clusters[c]);
  return out;
}

}  // namespace cropsight::segmentation
