#pragma once
// Order statistics of a list of numbers, the one definition every module uses (size metrics, the
// size-bias fit, latency percentiles, probes). Header-only and C++17, so that the ROS nodes use it
// too. The argument is taken by value: the caller's vector keeps its order.
#include <algorithm>
#include <cstddef>
#include <limits>
#include <vector>

namespace cropsight {

/// The middle value; for an even count the mean of the two middle values. NaN when empty.
inline double median(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  const std::size_t m = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(m), v.end());
  const double hi = v[m];
  if (v.size() % 2) return hi;
  const double lo = *std::max_element(v.begin(), v.begin() + std::ptrdiff_t(m));
  return 0.5 * (lo + hi);
}

/// The q-quantile (q in [0, 1]) by nearest rank: the value at index round(q·(n − 1)) of the sorted
/// values, so q = 0.99 of 100 latencies is the 99th smallest. NaN when empty.
inline double quantile(std::vector<double> v, double q) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  const double pos = std::clamp(q, 0.0, 1.0) * double(v.size() - 1) + 0.5;
  const std::size_t k = std::min(v.size() - 1, std::size_t(pos));
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
  return v[k];
}

}  // namespace cropsight
