#pragma once
// The k-th smallest of a list of floats, the value std::nth_element would place at position k,
// by one counting pass into value buckets and a selection inside the one bucket that holds it
// (internal to the tracking module; used per detection for the head's top depth).
//
// Why: the top-of-head centroid takes the 2nd percentile of ~2000 depths per detection, and
// std::nth_element's partitioning was ~10 % of sizing + tracking's per-frame time (the
// 0.5 ms budget). Bucket b holds the values v with floor((v − lo) · B / (hi − lo)) = b (clamped to
// B − 1); that map is monotone in v under float rounding, so every value of bucket b is at least
// every value of bucket b − 1 and the k-th smallest is the (k − values before)-th of its bucket.
// tests/tracking/test_order_statistic.cpp checks it against std::nth_element.
//
// Thread-safety: a pure function of its arguments (`values` and `scratch` are reordered).
#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

namespace cropsight::tracking {

/// `values` finite, k < values.size(). Reorders `values`; `scratch` is a reusable buffer.
inline float kth_smallest(std::vector<float>& values, std::size_t k, std::vector<float>& scratch) {
  constexpr int kBuckets = 64;
  const std::size_t n = values.size();
  if (n < 4 * kBuckets) {  // small lists: the partitioning is cheap enough
    std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(k), values.end());
    return values[k];
  }
  float lo = values[0], hi = values[0];
  for (float v : values) lo = std::min(lo, v), hi = std::max(hi, v);
  if (!(hi > lo)) return lo;  // all equal
  const float scale = float(kBuckets) / (hi - lo);
  auto bucket = [lo, scale](float v) { return std::min(kBuckets - 1, int((v - lo) * scale)); };
  std::array<std::size_t, kBuckets> count{};
  for (float v : values) ++count[std::size_t(bucket(v))];
  std::size_t before = 0;
  int b = 0;
  while (before + count[std::size_t(b)] <= k) before += count[std::size_t(b++)];
  scratch.clear();
  for (float v : values)
    if (bucket(v) == b) scratch.push_back(v);
  const std::size_t j = k - before;
  std::nth_element(scratch.begin(), scratch.begin() + std::ptrdiff_t(j), scratch.end());
  return scratch[j];
}

}  // namespace cropsight::tracking
