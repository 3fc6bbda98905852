// cropsight simulate potato: a D415-like camera on an arm that scans potatoes hanging
// among roots and approaches one, with per-frame ground truth (docs/simulator.md, "Potatoes").
#include <cstdint>
#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/sim/potato/potato_sim.hpp"

namespace cropsight::cli {

namespace simulate_potato_cmd {
struct SimulatePotatoOptions {
  std::string scene = "sheet";
  int frames = 60;
  std::uint64_t seed = 1;
  std::string out;
  bool force = false, quiet = false;
  CommonOptions common;
};

void run_simulate_potato(const SimulatePotatoOptions& o) {
  if (o.frames < 1) throw Error("--frames", "must be at least 1");
  sim::PotatoSimConfig cfg;
  const std::string where = o.common.config.empty() ? "--set" : o.common.config;
  ConfigMap m = o.common.config_map("");
  if (!m.count("scene")) m["scene"] = o.scene;
  apply_config(cfg, m, where);
  cfg.validate(where);
  Progress progress("simulate potato", o.frames, o.common.json || o.quiet);
  const auto s = sim::simulate_potato_sequence(cfg, o.seed, o.frames, o.out,
                                               output_policy("simulate potato", o.force, {o.common.config}),
                                               [&](int done, int) { progress.update(done); });
  progress.finish();
  if (o.common.json) {
    print_json({{"out", o.out},
                {"scene", config_name(cfg.scene)},
                {"seed", o.seed},
                {"frames", s.frames},
                {"potatoes", s.potatoes},
                {"valid_fraction", s.valid_fraction},
                {"seconds", s.seconds}});
  } else {
    std::cout << "wrote " << o.out << ": " << s.frames << " frames, " << s.potatoes << " potatoes ("
              << config_name(cfg.scene) << "), valid depth " << s.valid_fraction << ", " << s.seconds << " s\n";
  }
}
}  // namespace simulate_potato_cmd

void add_simulate_potato(CLI::App& simulate) {
  using namespace simulate_potato_cmd;
  auto o = std::make_shared<SimulatePotatoOptions>();
  auto* cmd = simulate.add_subcommand("potato", "Simulate a D415 on an arm approaching potatoes in aeroponics");
  cmd->add_option("--scene", o->scene, "Backdrop: sheet, room or chamber")
      ->check(CLI::IsMember({"sheet", "room", "chamber"}));
  cmd->add_option("--frames", o->frames, "Number of frames")->default_val(60);
  cmd->add_option("--seed", o->seed, "Random seed (same seed and options = identical output)")->default_val(1);
  cmd->add_option("--out", o->out, "New sequence folder to write")->required();
  add_force_flag(cmd, o->force);
  cmd->add_flag("--quiet", o->quiet, "No progress lines");
  add_json_flag(cmd, o->common);
  add_config_options(cmd, o->common);
  cmd->callback([o] { run_simulate_potato(*o); });
}

}  // namespace cropsight::cli
