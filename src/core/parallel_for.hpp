#pragma once
// Private helper: the library's one parallel loop over rows. Every loop whose rows are written
// independently and whose thread count a user sets (pipeline::grape::FeatureConfig::threads, GbdtConfig::
// nthread, the carry-back's threads, ...) goes through parallel_for(), so that a limit means the
// same everywhere: at most `threads` threads, the calling thread one of them. TBB does the work
// (src/core/parallel_for.cpp, in a tbb::task_arena of that size); this header stays free of TBB.
#include <cstddef>
#include <memory>
#include <type_traits>

namespace cropsight::detail {

/// One call of the loop body on rows [begin, end) (ctx: the caller's callable).
using RangeBody = void (*)(const void* ctx, std::size_t begin, std::size_t end);

/// The threads a loop with no limit of its own uses: TBB's default concurrency (the cores this
/// process may run on).
int all_threads();

/// parallel_for() without the template (defined in parallel_for.cpp).
void parallel_for_ranges(std::size_t n, int threads, std::size_t grain, RangeBody body, const void* ctx);

/// Runs fn(begin, end) over contiguous pieces covering [0, n) exactly once, on at most `threads`
/// threads (values below 1 count as 1), the calling thread being one of them. Pieces have at
/// least `grain` rows; an input of fewer than two grains, or threads = 1, runs as one call
/// fn(0, n) on the calling thread (also for n = 0). Which thread gets which piece varies from
/// run to run, so fn must write each row independently of the others (then the result does not
/// depend on the split nor on the thread count). fn is called concurrently: it must be callable
/// as const. Returns when every piece is done; an exception thrown by fn is rethrown here.
template <class Fn>
void parallel_for(std::size_t n, int threads, std::size_t grain, const Fn& fn) {
  static_assert(std::is_invocable_v<const Fn&, std::size_t, std::size_t>, "fn(begin, end)");
  parallel_for_ranges(
      n, threads, grain, [](const void* ctx, std::size_t b, std::size_t e) { (*static_cast<const Fn*>(ctx))(b, e); },
      std::addressof(fn));
}

/// fn(i) for every i in [0, n), on all_threads() threads; the same contract as parallel_for.
template <class Fn>
void parallel_for_each_index(std::size_t n, const Fn& fn) {
  parallel_for(n, all_threads(), 1, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) fn(i);
  });
}

}  // namespace cropsight::detail
