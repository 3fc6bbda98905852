// cropsight batch: many recordings as shards, on this machine or as a Slurm job array, resumable,
// merged into one field map (docs/batch.md). The work is the library's (batch/batch_run.hpp); this
// file maps options to it and prints the summary.
//   exit 0  every shard done and merged; 2  bad manifest, recording or --out (nothing submitted);
//   exit 3  some shards still failed after the retries (the summary names them; rerun to resume)
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/batch/batch_run.hpp"
#include "cropsight/core/error.hpp"

namespace cropsight::cli {

namespace batch_cmd {
struct BatchCliOptions {
  std::string manifest, out, engine = "local";
  int workers = 1;
  bool dry_run = false, quiet = false, force = false;
  CommonOptions common;  // --json only
  std::string partition, account, time, mem;
  int cpus_per_task = 0, max_retries = -1;
  double poll_s = 1.0;
};

// The manifest's Slurm options with the command line's overrides.
batch::SlurmRun slurm_run(const BatchCliOptions& o, const batch::Manifest& m) {
  batch::SlurmRun run{m.slurm, std::filesystem::read_symlink("/proc/self/exe").string(), o.poll_s};
  if (!o.partition.empty()) run.options.partition = o.partition;
  if (!o.account.empty()) run.options.account = o.account;
  if (!o.time.empty()) run.options.time = o.time;
  if (!o.mem.empty()) run.options.mem = o.mem;
  if (o.cpus_per_task > 0) run.options.cpus_per_task = o.cpus_per_task;
  if (o.max_retries >= 0) run.options.max_retries = o.max_retries;
  return run;
}

void dry_run(const BatchCliOptions& o, const batch::Manifest& m, const batch::BatchOptions& options) {
  const batch::BatchPlan plan = batch::plan_batch(m);
  batch::check_geo_origins(plan);
  std::cout << plan.shards.size() << " shards:\n";
  for (const auto& s : plan.shards)
    std::cout << "  " << s.name << "  frames " << s.first_frame << "-" << s.end_frame << " (owns " << s.own_first << "-"
              << s.own_end << ")  " << s.sequence.string() << "\n";
  if (o.engine == "slurm") std::cout << "\n" << batch::sbatch_script(o.out, options.slurm);
}

void run(const BatchCliOptions& o) {
  const batch::Manifest manifest = batch::read_manifest(o.manifest);
  batch::BatchOptions options;
  options.engine = o.engine;
  options.workers = o.workers;
  options.force = o.force;
  if (o.workers < 1) throw Error("--workers", "must be at least 1");
  options.slurm = slurm_run(o, manifest);
  if (o.dry_run) return dry_run(o, manifest, options);
  const bool quiet = o.quiet || o.common.json;
  const auto log = [quiet](const std::string& line) {
    if (!quiet) std::fprintf(stderr, "batch: %s\n", line.c_str());
  };
  const batch::BatchResult r = batch::run_batch(manifest, o.out, options, log);
  if (o.common.json) {
    std::cout << batch::batch_summary_json(r);
  } else {
    const auto& e = r.engine;
    std::printf("%zu shards: %zu done before, %zu ran, %zu failed, %zu resubmitted; %.4f CPU-hours, %.1f s\n",
                e.planned, e.already_done, e.ran, e.failed, e.resubmitted, e.cpu_s / 3600.0, e.wall_s);
    for (const auto& line : e.errors) std::printf("  %s\n", line.c_str());
    if (r.merged && r.plan.crop != "broccoli")
      std::printf("wrote %s/%s: %zu rows of %zu recordings (sums in passes.csv)\n", o.out.c_str(),
                  r.concat.file.c_str(), r.concat.rows, r.concat.recordings.size());
    else if (r.merged)
      std::printf("merged %zu maps of %zu passes: %zu heads (%zu harvestable)%s; wrote %s/field-map.csv\n",
                  r.merge.maps, r.merge.passes, r.merge.heads_out, r.merge.harvestable,
                  r.merge.geo ? " with WGS84 (field-map.geojson)" : "", o.out.c_str());
  }
  if (!r.merged) {
    std::fflush(stdout);
    std::exit(3);  // documented above: the batch is resumable, its folder stays
  }
}
}  // namespace batch_cmd

void add_batch(CLI::App& app) {
  using namespace batch_cmd;
  auto o = std::make_shared<BatchCliOptions>();
  auto* cmd =
      app.add_subcommand("batch", "Run many recordings as shards (local or Slurm), resumable, and merge the maps");
  cmd->add_option("--manifest", o->manifest, "Batch manifest: YAML, or CSV with one row a recording (docs/batch.md)")->required();
  cmd->add_option("--out", o->out, "Batch folder: new, or an earlier run of this batch to resume")->required();
  cmd->add_option("--engine", o->engine, "local (threads on this machine) or slurm (a job array)")
      ->check(CLI::IsMember({"local", "slurm"}));
  cmd->add_option("--workers", o->workers, "Local engine: shards at a time")->default_val(1);
  cmd->add_flag("--dry-run", o->dry_run, "Print the shards (and the Slurm job script); run and write nothing");
  cmd->add_option("--partition", o->partition, "Slurm partition (overrides the manifest)");
  cmd->add_option("--account", o->account, "Slurm account (overrides the manifest)");
  cmd->add_option("--time", o->time, "Slurm time limit per task, e.g. 01:00:00 (overrides the manifest)");
  cmd->add_option("--mem", o->mem, "Slurm memory per task, e.g. 2G (overrides the manifest)");
  cmd->add_option("--cpus-per-task", o->cpus_per_task, "Slurm CPUs per task (overrides the manifest)");
  cmd->add_option("--max-retries", o->max_retries, "Resubmissions of a failed array task (overrides the manifest)");
  cmd->add_option("--poll", o->poll_s, "Seconds between squeue polls")->default_val(1.0);
  cmd->add_flag("--force", o->force,
                "Start over in --out when it holds an earlier cropsight output (without: resume the same batch)");
  cmd->add_flag("--quiet", o->quiet, "No progress lines");
  add_json_flag(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
