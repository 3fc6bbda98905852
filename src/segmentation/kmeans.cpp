#include "cropsight/segmentation/kmeans.hpp"

#include <limits>
#include <random>

#include "cropsight/core/error.hpp"
#include "kmeans_seed.hpp"

namespace cropsight::segmentation {

std::vector<Eigen::Vector3d> kmeanspp_seeds(const std::vector<Eigen::Vector3f>& points, int k, std::uint32_t seed) {
  std::mt19937 rng(seed);
  const int n = int(points.size());
  std::vector<Eigen::Vector3d> seeds{points[std::uniform_int_distribution<int>(0, n - 1)(rng)].cast<double>()};
  std::vector<double> d2(n, std::numeric_limits<double>::max());
  while (int(seeds.size()) < k) {
    double total = 0;
    for (int i = 0; i < n; ++i) {
      d2[i] = std::min(d2[i], (points[i].cast<double>() - seeds.back()).squaredNorm());
      total += d2[i];
    }
    int pick = n - 1;
    double u = std::uniform_real_distribution<double>(0, total)(rng);
    for (int i = 0; i < n; ++i) {
      u -= d2[i];
      if (u <= 0) {
        pick = i;
        break;
      }
    }
    seeds.push_back(points[pick].cast<double>());
  }
  return seeds;
}

HardClustering kmeans(const std::vector<Eigen::Vector3f>& points, const KMeansConfig& cfg, const std::string& where) {
  if (cfg.clusters < 1) throw Error(where, "clusters must be >= 1");
  if (int(points.size()) < cfg.clusters) throw Error(where, "fewer points than clusters");
  const int n = int(points.size()), k = cfg.clusters;
  HardClustering r;
  r.centres = kmeanspp_seeds(points, k, cfg.seed);
  r.labels.assign(n, 0);
  for (r.iterations = 1; r.iterations <= cfg.max_iterations; ++r.iterations) {
    std::vector<Eigen::Vector3d> sum(k, Eigen::Vector3d::Zero());
    std::vector<int> count(k, 0);
    r.inertia = 0;
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3d p = points[i].cast<double>();
      double best = std::numeric_limits<double>::max();
      for (int j = 0; j < k; ++j) {
        const double d = (p - r.centres[j]).squaredNorm();
        if (d < best) best = d, r.labels[i] = j;
      }
      r.inertia += best;
      sum[r.labels[i]] += p;
      ++count[r.labels[i]];
    }
    double moved = 0;
    for (int j = 0; j < k; ++j) {
      if (!count[j]) continue;  // an empty cluster keeps its centre
      const Eigen::Vector3d c = sum[j] / double(count[j]);
      moved = std::max(moved, (c - r.centres[j]).norm());
      r.centres[j] = c;
    }
    if (moved <= cfg.tolerance) break;
  }
  r.iterations = std::min(r.iterations, cfg.max_iterations);
  return r;
}

}  // namespace cropsight::segmentation
