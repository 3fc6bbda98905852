// cropsight simulate grape: one grape bunch's ROI cloud in the grape dataset's text format, with
// the true label of every point and the simulator's truth (docs/simulator.md, "Grape bunches").
// The folder is written whole at the end (io::OutputFolder): either complete or untouched.
#include <cstdint>
#include <cstdio>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/output.hpp"
#include "cropsight/sim/grape/grape_sim.hpp"

namespace cropsight::cli {

namespace simulate_grape_cmd {
struct SimulateGrapeOptions {
  CommonOptions common;
  std::string out;
  std::uint64_t seed = 1;
  bool force = false;
};

void run(const SimulateGrapeOptions& o) {
  const std::string where = o.common.config.empty() ? "--set" : o.common.config;
  sim::GrapeSimConfig cfg;
  apply_config(cfg, o.common.config_map(), where);
  cfg.validate(where);
  io::OutputFolder out(o.out, output_policy("simulate grape", o.force, {o.common.config}));
  const sim::GrapeSimCloud s = sim::simulate_grape_cloud(cfg, o.seed);
  sim::write_grape_sim(out.path(), s);
  out.commit("grape cloud");
  const auto& c = s.truth.label_counts;
  if (o.common.json) {
    print_json({{"out", o.out},
                {"seed", o.seed},
                {"points", s.cloud.size()},
                {"label_counts", c},
                {"berries", s.truth.berries},
                {"leaves", s.truth.leaves},
                {"distance_m", s.truth.distance_m},
                {"scale_m", s.scale}});
  } else {
    std::printf("wrote %s: %zu points (berries %ld, peduncle %ld, leaf %ld, backdrop %ld, noise %ld, no return %ld)\n",
                o.out.c_str(), s.cloud.size(), c[1], c[2], c[3], c[4], c[5], c[0]);
  }
}
}  // namespace simulate_grape_cmd

void add_simulate_grape(CLI::App& simulate) {
  using namespace simulate_grape_cmd;
  auto o = std::make_shared<SimulateGrapeOptions>();
  auto* cmd = simulate.add_subcommand("grape", "One grape bunch's ROI cloud (text format, true labels) and its truth");
  cmd->add_option("--out", o->out, "New output folder: cloud.txt, truth.json (written whole at the end)")->required();
  cmd->add_option("--seed", o->seed, "Random seed (same seed and options = identical output)")->default_val(1);
  add_force_flag(cmd, o->force);
  add_json_flag(cmd, o->common);
  add_config_options(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
