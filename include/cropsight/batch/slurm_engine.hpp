#pragma once
// The Slurm engine: the missing shards of a batch as one job array (task id = shard index in
// plan.json), followed to the end and resubmitted where a task failed.
//
//   1. write DIR/slurm/batch.sbatch (sbatch_script: #SBATCH lines from SlurmOptions, one command:
//      `cropsight batch-shard --batch-dir DIR --index $SLURM_ARRAY_TASK_ID`);
//   2. `sbatch --parsable --array=I,J,...[%max_parallel] DIR/slurm/batch.sbatch`;
//   3. poll `squeue -h -j JOB` until the job has left the queue, then keep `scontrol show job JOB`
//      (every array task's state and exit code) in DIR/slurm/JOB.scontrol.txt;
//   4. the shards still without a done folder are resubmitted as a new array, up to
//      SlurmOptions::max_retries times; what is still missing then is reported as failed.
//
// Step 4 decides by the shard folders, not by Slurm's exit codes: a folder exists only when its
// shard finished (shard_runner.hpp), whatever the scheduler says (a node lost after the rename,
// a task killed at its time limit before it). Accounting (sacct) is not needed: CPU time comes
// from the shards' own shard.json.
#include <filesystem>
#include <string>
#include <vector>

#include "cropsight/batch/engine.hpp"
#include "cropsight/batch/manifest.hpp"

namespace cropsight::batch {

struct SlurmRun {
  SlurmOptions options;          ///< the manifest's, with the command line's overrides
  std::string cropsight_binary;  ///< absolute path of the program the tasks run
  double poll_s = 1.0;           ///< squeue interval
};

/// The job script (shown by `batch --dry-run`).
std::string sbatch_script(const std::filesystem::path& dir, const SlurmRun& run);
/// "0,2,5%2": Slurm's --array value for `indices` with the throttle `max_parallel` (0 = none).
std::string array_spec(const std::vector<std::size_t>& indices, int max_parallel);
/// Runs the missing shards of `plan` as above. Throws Error("sbatch", ...) when the scheduler
/// refuses the job or cannot be reached.
EngineReport run_slurm(const BatchPlan& plan, const std::filesystem::path& dir, const SlurmRun& run,
                       const BatchLog& log = {});

}  // namespace cropsight::batch
