// cropsight batch-shard: one shard of a planned batch (what each Slurm array task runs; the local
// engine runs the same library call on its threads). A shard already done is left as it is.
#include <cstdio>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/batch/plan.hpp"
#include "cropsight/batch/shard_runner.hpp"
#include "cropsight/core/error.hpp"

namespace cropsight::cli {

namespace batch_shard_cmd {
struct ShardCliOptions {
  std::string batch;
  long index = -1;
};

void run(const ShardCliOptions& o) {
  const batch::BatchPlan plan = batch::read_plan(std::filesystem::path(o.batch) / "plan.json");
  if (o.index < 0 || std::size_t(o.index) >= plan.shards.size())
    throw Error("--index", "must lie in [0, " + std::to_string(plan.shards.size()) + ")");
  const batch::Shard& shard = plan.shards[std::size_t(o.index)];
  if (batch::shard_done(o.batch, shard)) {
    std::printf("shard %s: already done\n", shard.name.c_str());
    return;
  }
  const batch::ShardRecord r = batch::run_shard(plan, std::size_t(o.index), o.batch);
  std::printf("shard %s: %d frames, %ld detections, %d kept, %.2f CPU s on %s\n", r.name.c_str(), r.frames,
              r.detections, r.items, r.cpu_s, r.host.c_str());
}
}  // namespace batch_shard_cmd

void add_batch_shard(CLI::App& app) {
  using namespace batch_shard_cmd;
  auto o = std::make_shared<ShardCliOptions>();
  auto* cmd = app.add_subcommand("batch-shard", "Run one shard of a planned batch (a Slurm array task's command)");
  cmd->add_option("--batch-dir", o->batch, "Batch folder holding plan.json (batch --out)")->required();
  cmd->add_option("--index", o->index, "Shard index in plan.json (the array task id)")->required();
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
