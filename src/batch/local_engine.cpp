// The local engine: the missing shards on N worker threads (batch/engine.hpp).
#include <atomic>
#include <mutex>
#include <thread>

#include "cropsight/batch/engine.hpp"
#include "cropsight/batch/shard_runner.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/core/timer.hpp"

namespace cropsight::batch {

namespace fs = std::filesystem;

std::vector<std::size_t> missing_shards(const BatchPlan& plan, const fs::path& dir) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < plan.shards.size(); ++i)
    if (!shard_done(dir, plan.shards[i])) out.push_back(i);
  return out;
}

EngineReport run_local(const BatchPlan& plan, const fs::path& dir, int workers, const BatchLog& log) {
  const Stopwatch clock;
  EngineReport report;
  report.planned = plan.shards.size();
  const auto todo = missing_shards(plan, dir);
  report.already_done = report.planned - todo.size();
  std::atomic<std::size_t> next{0};
  std::mutex mutex;  // guards report and log
  auto worker = [&] {
    for (std::size_t k = next++; k < todo.size(); k = next++) {
      const Shard& shard = plan.shards[todo[k]];
      try {
        const ShardRecord r = run_shard(plan, todo[k], dir);
        const std::lock_guard lock(mutex);
        report.ran += 1;
        report.cpu_s += r.cpu_s;
        report.frames += r.frames;
        if (log)
          log("shard " + shard.name + " done (" + std::to_string(report.ran) + "/" + std::to_string(todo.size()) + ")");
      } catch (const std::exception& e) {
        const std::lock_guard lock(mutex);
        report.failed += 1;
        report.errors.push_back("shard " + shard.name + ": " + e.what());
        if (log) log(report.errors.back());
      }
    }
  };
  std::vector<std::thread> threads;
  for (int t = 0; t < std::max(1, workers); ++t) threads.emplace_back(worker);
  for (auto& t : threads) t.join();
  report.wall_s = clock.seconds();
  return report;
}

}  // namespace cropsight::batch
