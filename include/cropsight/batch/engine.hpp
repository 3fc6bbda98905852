#pragma once
// The engines that run a batch's missing shards: on this machine (run_local) or as a Slurm job
// array (slurm_engine.hpp). Both write the same shard folders, so the merge that follows gives
// the same bytes whichever ran them.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "cropsight/batch/plan.hpp"

namespace cropsight::batch {

/// What an engine did in this run.
struct EngineReport {
  std::size_t planned = 0;           ///< shards in the plan
  std::size_t already_done = 0;      ///< done before this run (skipped)
  std::size_t ran = 0;               ///< done by this run
  std::size_t failed = 0;            ///< still not done at the end
  std::size_t resubmitted = 0;       ///< array tasks submitted again (Slurm)
  double cpu_s = 0.0;                ///< CPU seconds of the shards this run finished (their shard.json)
  double wall_s = 0.0;               ///< this run, seconds
  long frames = 0;                   ///< frames processed by the shards this run finished
  std::vector<std::string> job_ids;  ///< Slurm jobs submitted
  std::vector<std::string> errors;   ///< one line per failed shard
};

/// A progress line ("shard row-01 done (3/8)"); may be empty.
using BatchLog = std::function<void(const std::string&)>;

/// The indices of the shards of `plan` not done in `dir`.
std::vector<std::size_t> missing_shards(const BatchPlan& plan, const std::filesystem::path& dir);

/// Runs the missing shards on `workers` threads (one pipeline each); a failed shard is reported
/// and the others go on.
EngineReport run_local(const BatchPlan& plan, const std::filesystem::path& dir, int workers, const BatchLog& log = {});

}  // namespace cropsight::batch
