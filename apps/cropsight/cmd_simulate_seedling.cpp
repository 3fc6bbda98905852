// cropsight simulate seedling (issue 5): stereo pairs of broccoli seedlings among weeds with
// ground truth, checkerboard pairs, and the rig's calibration (rig.yaml).
#include <cstdio>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/sim/seedling.hpp"
#include "cropsight/stereo/calibration.hpp"

namespace cropsight::cli {

namespace {

struct Options {
  CommonOptions common;
  std::string out;
  int pairs = 20, calib_pairs = 12;
  std::uint64_t seed = 1;
  bool quiet = false;
};

void run(const Options& o) {
  sim::SeedlingSimConfig cfg;
  apply_config(cfg, o.common.config_map(), o.common.config.empty() ? "--set" : o.common.config);
  if (o.pairs < 0) throw Error("--pairs", "must be >= 0");
  Progress progress("simulate seedling", o.pairs, o.quiet || o.common.json);
  sim::write_seedling_dataset(
      o.out, cfg, o.pairs, o.seed, o.calib_pairs, [](int done, void* p) { static_cast<Progress*>(p)->update(done); },
      &progress);
  progress.finish();
  // The simulated views are already rectified: the rig's calibration is ideal.
  const sim::StereoRigModel rig = cfg.rig();
  stereo::StereoCalibration c;
  c.width = rig.width;
  c.height = rig.height;
  c.K1 << rig.f, 0, rig.cx, 0, rig.f, rig.cy, 0, 0, 1;
  c.K2 = c.K1;
  c.D1 = c.D2 = std::vector<double>(5, 0.0);
  c.R = rig.R;
  c.T = rig.T;
  Eigen::Matrix3d tx;
  tx << 0, -c.T.z(), c.T.y(), c.T.z(), 0, -c.T.x(), -c.T.y(), c.T.x(), 0;
  c.E = tx * c.R;
  c.F = c.K2.inverse().transpose() * c.E * c.K1.inverse();
  stereo::save_calibration(std::filesystem::path(o.out) / "rig.yaml", c);
  if (o.common.json)
    print_json({{"out", o.out}, {"pairs", o.pairs}, {"calib_pairs", o.calib_pairs}, {"seed", o.seed}});
  else
    std::printf("wrote %d seedling pairs and %d checkerboard pairs to %s (rig.yaml: ideal rig)\n", o.pairs,
                o.calib_pairs, o.out.c_str());
}

}  // namespace

void add_simulate_seedling(CLI::App& simulate) {
  auto o = std::make_shared<Options>();
  auto* cmd = simulate.add_subcommand("seedling", "Stereo pairs of broccoli seedlings with ground truth (issue 5)");
  cmd->add_option("--out", o->out, "Output folder")->required();
  cmd->add_option("--pairs", o->pairs, "Seedling stereo pairs")->capture_default_str();
  cmd->add_option("--seed", o->seed, "Random seed (same seed, same data)")->capture_default_str();
  cmd->add_option("--calib-pairs", o->calib_pairs, "Checkerboard pairs under calib/")->capture_default_str();
  cmd->add_flag("--quiet", o->quiet, "No progress line");
  add_json_flag(cmd, o->common);
  add_config_options(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
