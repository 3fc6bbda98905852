#pragma once
// Sampling a cloud to the fixed point count a network takes (farthest-point or uniform random),
// and carrying per-sample predictions back to every original point by nearest neighbour.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace cropsight::geometry {

/// Farthest-point sampling: starts at `start`, then repeatedly adds the point farthest from
/// those chosen (Euclidean). Returns `count` distinct indices in selection order; when count >=
/// size, every index. Same algorithm as pcl::FarthestPointSampling (compared in the tests).
std::vector<int> farthest_point_sample(const std::vector<Eigen::Vector3f>& points, std::size_t count,
                                       std::size_t start = 0);

/// `count` indices drawn uniformly without replacement (std::mt19937 seeded by `seed`); when
/// count > size, every index once then repeats drawn with replacement, so that the result
/// always has exactly `count` entries (networks need a fixed count).
std::vector<int> random_sample(std::size_t size, std::size_t count, std::uint64_t seed);

/// For each point of `all`, the index (into `samples`) of its nearest sample.
std::vector<int> nearest_sample(const std::vector<Eigen::Vector3f>& samples, const std::vector<Eigen::Vector3f>& all);

/// Labels of `samples` carried back to every point of `all` by nearest neighbour.
std::vector<int> carry_labels_back(const std::vector<Eigen::Vector3f>& samples, const std::vector<int>& sample_labels,
                                   const std::vector<Eigen::Vector3f>& all);

}  // namespace cropsight::geometry
