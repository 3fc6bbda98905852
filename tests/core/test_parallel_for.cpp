// The one parallel loop (src/core/parallel_for.hpp): every row once, small inputs on the calling
// thread, at most `threads` threads, exceptions reach the caller.
#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include "core/parallel_for.hpp"

using cropsight::detail::parallel_for;

TEST(ParallelFor, EveryRowExactlyOnce) {
  for (std::size_t n : {0u, 1u, 255u, 256u, 1000u, 100000u})
    for (int threads : {1, 2, 3, 8}) {
      std::vector<std::atomic<int>> hits(n);
      parallel_for(n, threads, 64, [&](std::size_t b, std::size_t e) {
        ASSERT_LE(b, e);
        ASSERT_LE(e, n);
        for (std::size_t i = b; i < e; ++i) hits[i].fetch_add(1);
      });
      for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(hits[i].load(), 1) << "n " << n << " threads " << threads;
    }
}

TEST(ParallelFor, SmallInputsAndOneThreadStayOnTheCaller) {
  const auto caller = std::this_thread::get_id();
  for (auto [count, threads] : {std::pair<std::size_t, int>{0, 4}, {100, 4}, {199, 4}, {100000, 1}, {100000, 0}}) {
    const std::size_t n = count;  // Clang 14 (the fuzz/sanitizer build) cannot capture a structured binding
    int calls = 0;
    parallel_for(n, threads, 100, [&](std::size_t b, std::size_t e) {
      ++calls;  // one call only, so no race
      EXPECT_EQ(std::this_thread::get_id(), caller);
      EXPECT_EQ(b, 0u);
      EXPECT_EQ(e, n);
    });
    EXPECT_EQ(calls, 1) << "n " << n << " threads " << threads;
  }
}

TEST(ParallelFor, AtMostThreadsThreads) {
  for (int threads : {2, 3}) {
    std::mutex m;
    std::set<std::thread::id> ids;
    std::atomic<int> active{0}, most{0};
    parallel_for(1 << 16, threads, 16, [&](std::size_t b, std::size_t e) {
      const int now = ++active;
      for (int seen = most.load(); now > seen && !most.compare_exchange_weak(seen, now);) {
      }
      {
        std::lock_guard<std::mutex> lock(m);
        ids.insert(std::this_thread::get_id());
      }
      volatile double s = 0;
      for (std::size_t i = b; i < e; ++i) s = s + double(i);
      --active;
    });
    EXPECT_LE(most.load(), threads);
    EXPECT_GE(ids.size(), 1u);
  }
}

TEST(ParallelFor, ExceptionsReachTheCaller) {
  EXPECT_THROW(parallel_for(10000, 2, 10,
                            [](std::size_t b, std::size_t e) {
                              if (b <= 5000 && 5000 < e) throw std::runtime_error("row 5000");
                            }),
               std::runtime_error);
}
