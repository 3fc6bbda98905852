#pragma once
// Private helper: runs fn(begin, end) over [0, n) split into `threads` contiguous shares, one
// std::thread per share beyond the first (which runs on the calling thread). Small inputs
// (fewer than min_per_thread rows per share) stay on the calling thread.
#include <algorithm>
#include <cstddef>
#include <thread>
#include <vector>

namespace cropsight::pipeline::detail {

template <class Fn>
void parallel_rows(std::size_t n, int threads, std::size_t min_per_thread, Fn&& fn) {
  const std::size_t t = std::max<std::size_t>(
      1, std::min<std::size_t>(std::size_t(std::max(threads, 1)), n / std::max<std::size_t>(min_per_thread, 1)));
  if (t <= 1) {
    fn(std::size_t(0), n);
    return;
  }
  const std::size_t chunk = (n + t - 1) / t;
  std::vector<std::thread> pool;
  for (std::size_t i = 1; i < t; ++i)
    pool.emplace_back([&fn, i, chunk, n] { fn(std::min(n, i * chunk), std::min(n, (i + 1) * chunk)); });
  fn(std::size_t(0), std::min(n, chunk));
  for (auto& th : pool) th.join();
}

}  // namespace cropsight::pipeline::detail
