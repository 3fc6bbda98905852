#include "cropsight/geometry/statistical_outlier.hpp"

#include <cmath>
#include <numeric>

#include "cropsight/core/error.hpp"
#include "geometry/point_kdtree.hpp"

namespace cropsight::geometry {

namespace {

// Core on packed points; returns positions (into the packed array) that are kept.
std::vector<int> sor_packed(const detail::PackedPoints& pts, const StatisticalOutlierConfig& cfg) {
  if (cfg.mean_k < 1) throw Error("statistical outlier", "mean_k must be at least 1");
  if (!std::isfinite(cfg.std_mul)) throw Error("statistical outlier", "std_mul must be finite");
  const std::size_t n = pts.kdtree_get_point_count();
  std::vector<int> kept;
  if (n < 2) {
    kept.resize(n);
    std::iota(kept.begin(), kept.end(), 0);
    return kept;
  }
  detail::PointKdTree tree(3, pts, detail::kdtree_params());
  tree.buildIndex();
  // k + 1 because the query point is its own nearest neighbour (PCL's convention); with fewer
  // points than that, all others are used (PCL's k-d tree does the same).
  const std::size_t k = std::min<std::size_t>(std::size_t(cfg.mean_k) + 1, n);
  std::vector<std::uint32_t> idx(k);
  std::vector<float> d2(k);
  std::vector<float> mean_dist(n);
  double sum = 0.0, sq_sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t found = tree.knnSearch(&pts.xyz[3 * i], k, idx.data(), d2.data());
    double s = 0.0;
    for (std::size_t j = 1; j < found; ++j) s += std::sqrt(double(d2[j]));
    // PCL divides by mean_k even when fewer neighbours exist.
    const float m = float(s / cfg.mean_k);
    mean_dist[i] = m;
    sum += m;
    sq_sum += double(m) * m;
  }
  const double mean = sum / double(n);
  const double var = (sq_sum - sum * sum / double(n)) / double(n - 1);
  const double threshold = mean + cfg.std_mul * std::sqrt(std::max(0.0, var));
  kept.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
    if (!(mean_dist[i] > threshold)) kept.push_back(int(i));
  return kept;
}

}  // namespace

std::vector<int> remove_statistical_outliers(const OrganizedCloud& cloud, const std::vector<int>& indices,
                                             const StatisticalOutlierConfig& cfg) {
  detail::PackedPoints pts;
  pts.xyz.resize(indices.size() * 3);
  for (std::size_t j = 0; j < indices.size(); ++j) {
    const int i = indices[j];
    if (i < 0 || std::size_t(i) >= cloud.size() || !cloud.valid(std::size_t(i)))
      throw Error("statistical outlier", "index " + std::to_string(i) + " is not a valid point of the cloud");
    pts.xyz[3 * j] = cloud.x[i];
    pts.xyz[3 * j + 1] = cloud.y[i];
    pts.xyz[3 * j + 2] = cloud.z[i];
  }
  std::vector<int> kept = sor_packed(pts, cfg);
  for (int& k : kept) k = indices[std::size_t(k)];
  return kept;
}

std::vector<int> remove_statistical_outliers(const std::vector<Eigen::Vector3f>& points,
                                             const StatisticalOutlierConfig& cfg) {
  detail::PackedPoints pts;
  pts.xyz.resize(points.size() * 3);
  for (std::size_t j = 0; j < points.size(); ++j) {
    if (!points[j].allFinite()) throw Error("statistical outlier", "point " + std::to_string(j) + " is not finite");
    pts.xyz[3 * j] = points[j].x();
    pts.xyz[3 * j + 1] = points[j].y();
    pts.xyz[3 * j + 2] = points[j].z();
  }
  return sor_packed(pts, cfg);
}

}  // namespace cropsight::geometry
