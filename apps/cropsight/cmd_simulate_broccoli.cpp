// cropsight simulate broccoli: a simulated Kinect v2 sequence over a broccoli field, with exact
// ground truth (docs/simulator.md).
#include <cmath>
#include <cstdint>
#include <iostream>
#include <optional>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/sim/broccoli/broccoli_sim.hpp"

namespace cropsight::cli {

namespace simulate_broccoli_cmd {
struct SimulateBroccoliOptions {
  std::string variety = "uk";
  int frames = 60;
  std::uint64_t seed = 1;
  std::optional<double> fps;  // unset = the preset's value
  std::string out;
  bool force = false, quiet = false;
  bool randomize = false;
  std::string geo_origin;  // "LAT,LON[,AZIMUTH]"
  CommonOptions common;
};

// "LAT,LON[,AZIMUTH]" (degrees) → the origin of the simulator's field frame on the Earth.
std::optional<io::GeoOrigin> parse_geo_origin(const std::string& text) {
  if (text.empty()) return std::nullopt;
  const auto parts = split_list(text, "--geo-origin");
  if (parts.size() < 2 || parts.size() > 3) throw Error("--geo-origin", "expected LAT,LON or LAT,LON,AZIMUTH");
  io::GeoOrigin g;
  double* targets[] = {&g.latitude_deg, &g.longitude_deg, &g.field_x_azimuth_deg};
  for (std::size_t k = 0; k < parts.size(); ++k) {
    std::size_t used = 0;
    try {
      *targets[k] = std::stod(parts[k], &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != parts[k].size()) throw Error("--geo-origin", "'" + parts[k] + "' is not a number");
  }
  g.validate("--geo-origin");
  return g;
}

void run_simulate_broccoli(const SimulateBroccoliOptions& o) {
  const io::OutputPolicy policy = output_policy("simulate broccoli", o.force, {o.common.config});
  if (o.frames < 1) throw Error("--frames", "must be at least 1");
  if (o.fps && !(std::isfinite(*o.fps) && *o.fps > 0.0)) throw Error("--fps", "must be a positive number");
  sim::BroccoliSimConfig cfg;
  // The variety picks the preset; --config replaces it with another file; --set overrides keys.
  const std::string where =
      o.common.config.empty() ? "configs/sim-broccoli-" + o.variety + ".yaml (with --set)" : o.common.config;
  apply_config(cfg, o.common.config_map("sim-broccoli-" + o.variety), where);
  if (o.fps) cfg.motion.fps = *o.fps;
  if (o.randomize) cfg.randomize.enabled = true;
  cfg.validate(where);
  const auto geo_origin = parse_geo_origin(o.geo_origin);

  Progress progress("simulate broccoli", o.frames, o.common.json || o.quiet);
  const auto summary = sim::simulate_broccoli_sequence(
      cfg, o.seed, o.frames, o.out, policy, [&](int done, int) { progress.update(done); }, geo_origin);
  progress.finish();
  if (o.common.json) {
    print_json({{"out", o.out},
                {"variety", cfg.field.variety},
                {"seed", o.seed},
                {"frames", summary.frames},
                {"instances", summary.instances},
                {"plants", summary.plants},
                {"harvested", summary.harvested},
                {"mean_occlusion", summary.mean_occlusion},
                {"valid_fraction", summary.valid_fraction},
                {"seconds", summary.seconds}});
  } else {
    std::cout << "wrote " << o.out << ": " << summary.frames << " frames, " << summary.instances
              << " ground-truth heads (" << summary.plants << " plants, " << summary.harvested
              << " harvested), mean occlusion " << summary.mean_occlusion << ", valid depth " << summary.valid_fraction
              << ", " << summary.seconds << " s\n";
  }
}
}  // namespace simulate_broccoli_cmd

void add_simulate_broccoli(CLI::App& simulate) {
  using namespace simulate_broccoli_cmd;
  auto o = std::make_shared<SimulateBroccoliOptions>();
  auto* cmd = simulate.add_subcommand("broccoli", "Simulate a tractor-mounted ToF camera over a broccoli field");
  cmd->add_option("--variety", o->variety,
                  "Field preset: uk (Ironman), spain (Titanium), random (randomised fields, training ranges) or "
                  "random-wide (wider ranges, for held-out evaluation)")
      ->check(CLI::IsMember({"uk", "spain", "random", "random-wide"}));
  cmd->add_flag("--randomize", o->randomize,
                "Draw this sequence's field, plants, heads, soil, camera and sensor from the randomize.* ranges "
                "(from the seed) on top of the preset (docs/simulator.md)");
  cmd->add_option("--frames", o->frames, "Number of frames")->default_val(60);
  cmd->add_option("--seed", o->seed, "Random seed (same seed and options = byte-identical output)")->default_val(1);
  cmd->add_option("--fps", o->fps, "Frame rate (default: the preset's 7.5; the datasets used 7.5, 3.3, 6.4)");
  cmd->add_option("--out", o->out, "New sequence folder to write")->required();
  cmd->add_option("--geo-origin", o->geo_origin,
                  "LAT,LON[,AZIMUTH]: WGS84 degrees of the field frame's origin and the compass azimuth of its x "
                  "axis (default 90, east); writes geo_origin.yaml (docs/formats.md)");
  add_force_flag(cmd, o->force);
  cmd->add_flag("--quiet", o->quiet, "No progress lines");
  add_json_flag(cmd, o->common);
  add_config_options(cmd, o->common);
  cmd->callback([o] { run_simulate_broccoli(*o); });
}

}  // namespace cropsight::cli
