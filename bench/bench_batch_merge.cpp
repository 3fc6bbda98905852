// The merge of field maps (batch/field_merge.hpp) against the number of passes and heads, on
// synthetic maps shaped like a broccoli field: rows 0.6 m apart along x, plants 0.38 m apart with
// 2.5 cm of jitter, every head seen by two passes (each pass a strip of rows, neighbouring strips
// sharing one row, as passes over overlapping rows do) with 1.5 cm of position noise per pass.
//
//   BM_Merge/P/H   P passes over a field of H heads (each pass's map: about 2H/P heads)
//
// Counters: heads_per_s = merged heads per second of merge (inputs read and outputs written are
// not counted: the batch's merge step times the same call). The processing it
// follows costs about 0.1 s of CPU per head-frame set (docs/batch.md), so the merge must stay
// orders of magnitude below it; docs/batch.md quotes these figures.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "cropsight/batch/field_merge.hpp"

using namespace cropsight;

namespace {

std::vector<batch::PassMap> synthetic_maps(int passes, long heads) {
  const int rows = std::max(2, int(std::lround(std::sqrt(double(heads) / 40.0))));  // a field ~ as long as wide
  const long per_row = std::max(1L, heads / rows);
  std::mt19937 rng(11);
  std::normal_distribution<double> jitter(0.0, 0.025), noise(0.0, 0.015);
  std::vector<batch::PassMap> maps{std::size_t(passes)};
  for (int p = 0; p < passes; ++p) maps[std::size_t(p)].pass = maps[std::size_t(p)].shard = "p" + std::to_string(p);
  // Passes split the field into `passes` blocks of (row, along-row) cells; a head belongs to its
  // block's pass and to the next block's pass (the overlap).
  const long total = long(rows) * per_row;
  for (int r = 0; r < rows; ++r)
    for (long k = 0; k < per_row; ++k) {
      const Eigen::Vector3d truth(0.38 * double(k) + jitter(rng), 0.6 * r + jitter(rng), 0.4);
      const long index = long(r) * per_row + k;
      const int p = int(index * passes / total);
      for (int q : {p, (p + 1) % passes}) {
        tracking::TrackedHead h;
        h.id = int(maps[std::size_t(q)].heads.size()) + 1;
        h.position = truth + Eigen::Vector3d(noise(rng), noise(rng), 0.0);
        h.frames_seen = 12;
        h.diameter_mm = h.bbox_mm = 120.0;
        maps[std::size_t(q)].heads.push_back(h);
      }
    }
  return maps;
}

void BM_Merge(benchmark::State& state) {
  const auto maps = synthetic_maps(int(state.range(0)), state.range(1));
  long inputs = 0;
  for (const auto& m : maps) inputs += long(m.heads.size());
  std::size_t merged = 0;
  for (auto _ : state) {
    const auto heads = batch::merge_field_maps(maps, batch::MergeRule{});
    merged = heads.size();
    benchmark::DoNotOptimize(heads.data());
  }
  state.counters["merged_heads"] = double(merged);
  state.counters["input_heads"] = double(inputs);
  state.counters["heads_per_s"] = benchmark::Counter(double(inputs), benchmark::Counter::kIsIterationInvariantRate);
}

}  // namespace

BENCHMARK(BM_Merge)
    ->Args({10, 1000})
    ->Args({100, 10000})
    ->Args({1000, 100000})
    ->Args({10000, 1000000})
    ->Args({10, 1000000})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK_MAIN();
