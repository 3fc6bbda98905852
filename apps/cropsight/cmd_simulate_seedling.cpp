// cropsight simulate seedling: stereo pairs of broccoli seedlings among weeds with
// ground truth, checkerboard pairs, and the rig's calibration (rig.yaml).
//
// The data set is written into a hidden temporary sibling of --out and renamed into place at the
// end (like simulate broccoli's sequence writer), so --out is either a complete data set or
// untouched: an interrupted run leaves no half data set that looks real, and a rerun with fewer
// pairs cannot leave the old run's pair_* folders next to the new rig.yaml.
#include <cstdio>
#include <filesystem>
#include <system_error>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/sim/seedling/seedling_sim.hpp"
#include "cropsight/stereo/calibration.hpp"

namespace cropsight::cli {

namespace simulate_seedling_cmd {

namespace fs = std::filesystem;

struct Options {
  CommonOptions common;
  std::string out;
  int pairs = 20, calib_pairs = 12;
  std::uint64_t seed = 1;
  bool quiet = false, force = false;
};

void run(const Options& o) {
  if (o.pairs < 1 || o.pairs > sim::kMaxSeedlingPairs)
    throw Error("--pairs",
                "must be in 1.." + std::to_string(sim::kMaxSeedlingPairs) + ", got " + std::to_string(o.pairs));
  if (o.calib_pairs < 0 || o.calib_pairs > sim::kMaxCalibrationPairs)
    throw Error("--calib-pairs", "must be in 0.." + std::to_string(sim::kMaxCalibrationPairs) + " (0 = none), got " +
                                     std::to_string(o.calib_pairs));
  // Checked before minutes of rendering, not after; removed on any failure, in place at the end.
  io::OutputFolder tmp(o.out, output_policy("simulate seedling", o.force, {o.common.config}));
  const fs::path& out = tmp.final_path();
  sim::SeedlingSimConfig cfg;
  apply_config(cfg, o.common.config_map(), o.common.config.empty() ? "--set" : o.common.config);
  Progress progress("simulate seedling", o.pairs, o.quiet || o.common.json);
  try {
    sim::write_seedling_dataset(
        tmp.path(), cfg, o.pairs, o.seed, o.calib_pairs,
        [](int done, void* p) { static_cast<Progress*>(p)->update(done); }, &progress);
    stereo::save_calibration(tmp.path() / "rig.yaml", sim::ideal_calibration(cfg.rig()));
  } catch (const Error& e) {
    throw Error(out.string(), e.problem());  // name --out, not the hidden temporary
  }
  progress.finish();

  // Into place; an old data set is swapped out in one step.
  tmp.commit("seedling data set");

  if (o.common.json)
    print_json({{"out", o.out}, {"pairs", o.pairs}, {"calib_pairs", o.calib_pairs}, {"seed", o.seed}});
  else
    std::printf("wrote %d seedling pairs and %d checkerboard pairs to %s (rig.yaml: ideal rig)\n", o.pairs,
                o.calib_pairs, o.out.c_str());
}

}  // namespace simulate_seedling_cmd

void add_simulate_seedling(CLI::App& simulate) {
  using namespace simulate_seedling_cmd;
  auto o = std::make_shared<Options>();
  auto* cmd = simulate.add_subcommand("seedling", "Stereo pairs of broccoli seedlings with ground truth");
  cmd->add_option("--out", o->out, "New output folder (written whole at the end)")->required();
  cmd->add_option("--pairs", o->pairs, "Seedling stereo pairs, 1..10000")->capture_default_str();
  cmd->add_option("--seed", o->seed, "Random seed (same seed, same data)")->capture_default_str();
  cmd->add_option("--calib-pairs", o->calib_pairs, "Checkerboard pairs under calib/, 0..1000 (0 = none)")
      ->capture_default_str();
  add_force_flag(cmd, o->force);
  cmd->add_flag("--quiet", o->quiet, "No progress line");
  add_json_flag(cmd, o->common);
  add_config_options(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
