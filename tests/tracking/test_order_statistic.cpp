// kth_smallest (src/tracking/order_statistic.hpp) against std::nth_element on the same lists.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "tracking/order_statistic.hpp"

using cropsight::tracking::kth_smallest;

namespace {
float reference(std::vector<float> v, std::size_t k) {
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
  return v[k];
}
}  // namespace

TEST(OrderStatistic, MatchesNthElement) {
  std::mt19937 rng(3);
  std::vector<float> scratch;
  int checked = 0;
  for (std::size_t n : {1u, 2u, 5u, 255u, 256u, 257u, 1000u, 2500u, 7000u}) {
    for (int kind = 0; kind < 5; ++kind) {
      std::vector<float> v(n);
      for (std::size_t i = 0; i < n; ++i) {
        switch (kind) {
          case 0:
            v[i] = std::uniform_real_distribution<float>(0.5f, 1.0f)(rng);
            break;  // depths
          case 1:
            v[i] = 0.001f * float(std::uniform_int_distribution<int>(700, 760)(rng));
            break;  // mm steps, ties
          case 2:
            v[i] = 0.75f;
            break;  // all equal
          case 3:
            v[i] = i == 0 ? -1e30f : std::uniform_real_distribution<float>(0.7f, 0.71f)(rng);
            break;  // one outlier
          default:
            v[i] = 0.9f - 0.0001f * float(i);
            break;  // sorted descending (raster order over a dome)
        }
      }
      for (std::size_t k : {std::size_t(0), std::size_t(0.02 * double(n - 1)), n / 2, n - 1}) {
        std::vector<float> w = v;
        EXPECT_EQ(kth_smallest(w, k, scratch), reference(v, k)) << "n " << n << " kind " << kind << " k " << k;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 100);
}
