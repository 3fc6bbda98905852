#include "cropsight/geometry/farthest_point.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <random>

#include "cropsight/core/error.hpp"
#include "cropsight/geometry/knn_normals.hpp"

namespace cropsight::geometry {

std::vector<int> farthest_point_sample(const std::vector<Eigen::Vector3f>& points, std::size_t count,
                                       std::size_t start) {
  const std::size_t n = points.size();
  if (count >= n) {
    std::vector<int> all(n);
    std::iota(all.begin(), all.end(), 0);
    return all;
  }
  if (start >= n) throw Error("farthest point sampling", "start index out of range");
  std::vector<float> dist(n, std::numeric_limits<float>::max());
  std::vector<int> out;
  out.reserve(count);
  std::size_t cur = start;
  dist[cur] = -1.f;
  out.push_back(int(cur));
  while (out.size() < count) {
    const Eigen::Vector3f c = points[cur];
    std::size_t best = 0;
    float best_d = -2.f;
    for (std::size_t i = 0; i < n; ++i) {
      if (dist[i] < 0) continue;
      // Euclidean (not squared) distance, so ties break exactly as in PCL's implementation.
      const float d = std::min(dist[i], (points[i] - c).norm());
      dist[i] = d;
      if (d > best_d) best_d = d, best = i;
    }
    cur = best;
    dist[cur] = -1.f;
    out.push_back(int(cur));
  }
  return out;
}

std::vector<int> random_sample(std::size_t size, std::size_t count, std::uint64_t seed) {
  if (size == 0) throw Error("random sampling", "empty cloud");
  std::mt19937_64 rng(seed);
  std::vector<int> idx(size);
  std::iota(idx.begin(), idx.end(), 0);
  std::shuffle(idx.begin(), idx.end(), rng);
  if (count <= size) {
    idx.resize(count);
    return idx;
  }
  std::uniform_int_distribution<int> pick(0, int(size) - 1);
  while (idx.size() < count) idx.push_back(pick(rng));
  return idx;
}

std::vector<int> nearest_sample(const std::vector<Eigen::Vector3f>& samples, const std::vector<Eigen::Vector3f>& all) {
  if (samples.empty()) throw Error("nearest sample", "no samples");
  PointIndex index(samples);
  std::vector<int> out(all.size());
  for (std::size_t i = 0; i < all.size(); ++i) out[i] = index.nearest(all[i]);
  return out;
}

std::vector<int> carry_labels_back(const std::vector<Eigen::Vector3f>& samples, const std::vector<int>& sample_labels,
                                   const std::vector<Eigen::Vector3f>& all) {
  if (samples.size() != sample_labels.size()) throw Error("carry labels back", "samples and labels differ in count");
  std::vector<int> nn = nearest_sample(samples, all);
  for (int& i : nn) i = sample_labels[std::size_t(i)];
  return nn;
}

}  // namespace cropsight::geometry
