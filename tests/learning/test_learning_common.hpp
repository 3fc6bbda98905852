#pragma once
// Synthetic data shared by the learning tests: two overlapping Gaussian classes.
#include <random>

#include "cropsight/learning/dataset.hpp"

namespace cropsight::learning::testdata {

/// n samples of dimension dim; positives (fraction pos_fraction) centred at +shift on the first
/// half of the features, negatives at 0; unit variance plus a per-feature offset and scale so
/// that standardisation matters.
inline Dataset gaussians(std::size_t n, int dim, double shift, std::uint32_t seed, double pos_fraction = 0.3) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> g(0.0f, 1.0f);
  std::bernoulli_distribution is_pos(pos_fraction);
  Dataset d(dim);
  std::vector<float> x(static_cast<std::size_t>(dim));
  for (std::size_t i = 0; i < n; ++i) {
    const int label = is_pos(rng) ? 1 : 0;
    for (int j = 0; j < dim; ++j) {
      const float mu = (label && j < dim / 2) ? float(shift) : 0.0f;
      x[std::size_t(j)] = 10.0f * float(j) + (0.5f + 0.1f * float(j)) * (mu + g(rng));
    }
    d.add(x, label);
  }
  return d;
}

}  // namespace cropsight::learning::testdata
