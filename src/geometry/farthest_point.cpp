#include "cropsight/geometry/farthest_point.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <random>

#include "cropsight/core/error.hpp"
#include "cropsight/geometry/knn_normals.hpp"
#include "geometry/farthest_point_step.hpp"

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
  // The points as three planes, so that each step's distance update runs eight points at a
  // time (geometry/farthest_point_step: the same float operations as the scalar loop this
  // replaced, so the same selection to the bit).
  std::vector<float> planes(3 * n);
  float *x = planes.data(), *y = x + n, *z = y + n;
  for (std::size_t i = 0; i < n; ++i) x[i] = points[i].x(), y[i] = points[i].y(), z[i] = points[i].z();
  std::vector<float> dist(n, std::numeric_limits<float>::max());
  std::vector<int> out;
  out.reserve(count);
  std::size_t cur = start;
  dist[cur] = -1.f;  // chosen: negative, never the farthest again
  out.push_back(int(cur));
  while (out.size() < count) {
    // Euclidean (not squared) distance, so ties break exactly as in PCL's implementation.
    cur = detail::farthest_point_step(x, y, z, dist.data(), n, x[cur], y[cur], z[cur]);
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
