#include "core/parallel_for.hpp"

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <exception>
#include <map>
#include <memory>
#include <thread>
#include <vector>

namespace cropsight::detail {

int all_threads() { return std::max(1, tbb::info::default_concurrency()); }

void parallel_for_ranges(std::size_t n, int threads, std::size_t grain, RangeBody body, const void* ctx) {
  grain = std::max<std::size_t>(grain, 1);
  // As many threads as there are whole grains, and no more than asked for.
  const std::size_t t = std::min<std::size_t>(std::size_t(std::max(threads, 1)), n / grain);
  if (t <= 1) {
    body(ctx, 0, n);
    return;
  }
#if defined(__SANITIZE_THREAD__)
  // ThreadSanitizer build (make tsan): TBB's library is not instrumented, so TSan cannot see its
  // synchronisation and reports every loop as a race inside TBB's inlined headers. Plain threads,
  // whose start and join TSan understands, run the same pieces concurrently instead, so races in
  // the loop bodies (ours) are still found.
  std::vector<std::thread> workers;
  std::vector<std::exception_ptr> errors(t);
  const std::size_t piece = (n + t - 1) / t;
  for (std::size_t k = 1; k < t && k * piece < n; ++k)  // no empty piece
    workers.emplace_back([&, k] {
      try {
        body(ctx, std::min(n, k * piece), std::min(n, (k + 1) * piece));
      } catch (...) {
        errors[k] = std::current_exception();
      }
    });
  try {
    body(ctx, 0, std::min(n, piece));
  } catch (...) {
    errors[0] = std::current_exception();
  }
  for (auto& w : workers) w.join();
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
  return;
#endif
  // The arena caps the concurrency at t (the calling thread joins it); TBB's own pool supplies
  // the workers, so no thread is started per call and nested loops do not oversubscribe. One
  // arena per calling thread and size, kept: a fresh arena per call made the caller spin while
  // TBB attached a worker to it (measured on bench_grape's 1024-row GBDT prediction: twice the
  // caller's CPU time, and slower), and per calling thread so that two callers still get
  // `threads` each, as with threads of their own.
  thread_local std::map<std::size_t, std::unique_ptr<tbb::task_arena>> arenas;
  std::unique_ptr<tbb::task_arena>& arena = arenas[t];
  if (!arena) arena = std::make_unique<tbb::task_arena>(static_cast<int>(t));
  arena->execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain),
                      [&](const tbb::blocked_range<std::size_t>& r) { body(ctx, r.begin(), r.end()); });
  });
}

}  // namespace cropsight::detail
