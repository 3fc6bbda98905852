#pragma once
// The output folder of a batch, DIR: filled shard by shard and resumed, never replaced.
//
//   DIR/.cropsight-output   the marker (io/output.hpp), command "batch", refreshed after each step
//   DIR/plan.json           the plan (plan.hpp): what every task runs
//   DIR/shards/NAME/        one folder per done shard (shard_runner.hpp)
//   DIR/slurm/              the job script, the tasks' logs, scontrol's view of each job
//   DIR/field-map.csv ...   the merge (batch_merge.hpp), summary.json, report.html
//
// A new or empty DIR starts a batch. A DIR that holds a batch of the same plan resumes it: only
// shards without a done folder run. Anything else (another plan, another command's output, a
// user's folder, a recording) is refused before any work, one Error naming DIR. With `force`, a
// DIR that is an earlier cropsight output holding only the files it lists (io/output.hpp) is
// removed and the batch starts over; a user's folder, or a batch folder a user added a file to,
// is still refused. The marker lists only the names a batch writes.
#include <filesystem>
#include <string>

#include "cropsight/batch/plan.hpp"

namespace cropsight::batch {

/// Opens DIR for `plan` as above; returns true when it resumes an earlier batch.
bool open_batch_folder(const std::filesystem::path& dir, const BatchPlan& plan, bool force = false);
/// Refreshes DIR's marker after a step (io::write_output_marker).
void mark_batch_folder(const std::filesystem::path& dir);

}  // namespace cropsight::batch
