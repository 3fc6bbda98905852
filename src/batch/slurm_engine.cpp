// The Slurm engine (batch/slurm_engine.hpp).
#include "cropsight/batch/slurm_engine.hpp"

#include <chrono>
#include <thread>

#include "cropsight/batch/shard_runner.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/io/files.hpp"
#include "shell_command.hpp"

namespace cropsight::batch {

namespace fs = std::filesystem;
using detail::run_command;
using detail::shell_quote;

namespace {

std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

std::string submit(const fs::path& script, const std::vector<std::size_t>& indices, int max_parallel) {
  const auto r = run_command({"sbatch", "--parsable", "--array=" + array_spec(indices, max_parallel), script.string()});
  if (r.exit_code != 0) throw Error("sbatch", "refused the job array: " + first_line(r.out));
  const std::string line = first_line(r.out);
  return line.substr(0, line.find(';'));  // "JOB" or "JOB;CLUSTER"
}

// Waits until `job` has left the queue; keeps scontrol's view of it.
void follow(const fs::path& dir, const std::string& job, double poll_s) {
  int errors = 0;
  for (;;) {
    std::this_thread::sleep_for(std::chrono::duration<double>(poll_s));
    const auto r = run_command({"squeue", "-h", "-j", job, "-o", "%i"});
    if (r.exit_code == 0 && r.out.find_first_not_of(" \n") == std::string::npos) break;
    if (r.exit_code != 0 && r.out.find("Invalid job id") != std::string::npos) break;  // purged already
    if (r.exit_code != 0 && ++errors >= 30)
      throw Error("squeue", "cannot follow job " + job + ": " + first_line(r.out));
  }
  const auto show = run_command({"scontrol", "show", "job", job});
  io::write_file_atomic(dir / "slurm" / (job + ".scontrol.txt"), show.out);
}

}  // namespace

std::string array_spec(const std::vector<std::size_t>& indices, int max_parallel) {
  std::string out;
  for (std::size_t i : indices) out += (out.empty() ? "" : ",") + std::to_string(i);
  if (max_parallel > 0) out += "%" + std::to_string(max_parallel);
  return out;
}

std::string sbatch_script(const fs::path& dir, const SlurmRun& run) {
  const SlurmOptions& o = run.options;
  const std::string d = fs::absolute(dir).lexically_normal().string();
  std::string s = "#!/bin/bash\n# cropsight batch: one array task per shard of " + d +
                  "/plan.json (task id = shard index).\n"
                  "# Submitted by `cropsight batch --engine slurm` with --array=<the missing shards>.\n"
                  "#SBATCH --job-name=cropsight-batch\n#SBATCH --output=" +
                  d + "/slurm/logs/%A_%a.log\n#SBATCH --cpus-per-task=" + std::to_string(o.cpus_per_task) +
                  "\n#SBATCH --time=" + o.time + "\n#SBATCH --mem=" + o.mem + "\n";
  if (!o.partition.empty()) s += "#SBATCH --partition=" + o.partition + "\n";
  if (!o.account.empty()) s += "#SBATCH --account=" + o.account + "\n";
  s += "set -eu\nexec " + shell_quote(run.cropsight_binary) + " batch-shard --batch-dir " + shell_quote(d) +
       " --index \"$SLURM_ARRAY_TASK_ID\"\n";
  return s;
}

EngineReport run_slurm(const BatchPlan& plan, const fs::path& dir, const SlurmRun& run, const BatchLog& log) {
  const Stopwatch clock;
  EngineReport report;
  report.planned = plan.shards.size();
  auto pending = missing_shards(plan, dir);
  report.already_done = report.planned - pending.size();
  const std::vector<std::size_t> todo = pending;
  fs::create_directories(dir / "slurm" / "logs");
  const fs::path script = dir / "slurm" / "batch.sbatch";
  io::write_file_atomic(script, sbatch_script(dir, run));
  for (int round = 0; !pending.empty() && round <= run.options.max_retries; ++round) {
    if (round > 0) report.resubmitted += pending.size();
    const std::string job = submit(script, pending, run.options.max_parallel);
    report.job_ids.push_back(job);
    if (log)
      log("job " + job + ": " + std::to_string(pending.size()) + " array tasks" + (round ? " (resubmitted)" : ""));
    follow(dir, job, run.poll_s);
    pending = missing_shards(plan, dir);
    if (log && !pending.empty()) log("job " + job + ": " + std::to_string(pending.size()) + " shards not done");
  }
  for (std::size_t i : todo) {
    if (!shard_done(dir, plan.shards[i])) continue;
    const ShardRecord r = read_shard_record(shard_folder(dir, plan.shards[i]) / "shard.json");
    report.ran += 1;
    report.cpu_s += r.cpu_s;
    report.frames += r.frames;
  }
  report.failed = pending.size();
  for (std::size_t i : pending)
    report.errors.push_back("shard " + plan.shards[i].name + ": not done after " +
                            std::to_string(run.options.max_retries + 1) + " attempts (logs in " +
                            (dir / "slurm" / "logs").string() + ")");
  report.wall_s = clock.seconds();
  return report;
}

}  // namespace cropsight::batch
