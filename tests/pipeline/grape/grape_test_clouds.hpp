#pragma once
// Tiny labelled grape clouds for the CLI tests: two separable blobs (label 1 left, label 3 right),
// unit normals and distinct colours, so a model can learn them in one short run.
#include <Eigen/Core>
#include <cstdint>
#include <random>

#include "cropsight/core/cloud.hpp"

namespace cropsight::testing {

/// `n` points (half per blob), deterministic in `seed`.
inline Cloud two_blobs(std::uint32_t seed, int n = 400) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> g;
  Cloud c;
  for (int i = 0; i < n; ++i) {
    const int l = i < n / 2 ? 1 : 3;
    const Eigen::Vector3f d = Eigen::Vector3f(g(rng), g(rng), g(rng)).normalized();
    c.points.push_back(0.3f * d + Eigen::Vector3f(l == 1 ? -0.4f : 0.4f, 0, 0));
    c.normals.push_back(d);
    c.colors.emplace_back(l == 1 ? 0.2f : 0.3f, l == 1 ? 0.1f : 0.7f, 0.2f);
    c.labels.push_back(l);
  }
  return c;
}

}  // namespace cropsight::testing
