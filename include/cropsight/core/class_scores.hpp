#pragma once
// Per-point class scores stored row-major (rows × classes): the label of each row is its
// largest score (the first on ties), as std::max_element picks.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace cropsight {

/// Argmax of every row of `scores` (rows × `classes`, row-major). `classes` must be > 0.
inline std::vector<int> argmax_rows(const float* scores, std::size_t rows, std::size_t classes) {
  std::vector<int> out(rows);
  for (std::size_t i = 0; i < rows; ++i) {
    const float* r = scores + i * classes;
    out[i] = int(std::max_element(r, r + classes) - r);
  }
  return out;
}

/// Class weights against imbalance for a class-weighted loss: (median count / count)^power for
/// each class with samples, the median taken over the classes present; 1 for absent classes.
/// power 0 gives equal weights, 1 full inverse frequency (the networks and the GBDT use 0.5).
inline std::vector<double> median_frequency_weights(const std::vector<double>& counts, double power) {
  std::vector<double> present;
  for (double c : counts)
    if (c > 0) present.push_back(c);
  std::vector<double> w(counts.size(), 1.0);
  if (present.empty()) return w;
  std::sort(present.begin(), present.end());
  const double median = present[present.size() / 2];
  for (std::size_t c = 0; c < counts.size(); ++c)
    if (counts[c] > 0) w[c] = std::pow(median / counts[c], power);
  return w;
}

}  // namespace cropsight
