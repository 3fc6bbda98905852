#pragma once
// Simulated broccoli frames for the pipeline tests (rendered in-process by the sim module).
#include <string>
#include <vector>

#include "cropsight/core/rgbd_frame.hpp"
#include "cropsight/io/config_yaml.hpp"
#include "cropsight/sim/broccoli/broccoli_sim.hpp"
#include "testing/testing.hpp"

namespace cropsight::testdata {

/// A shipped simulator preset, configs/sim-broccoli-<name>.yaml applied to the defaults and
/// validated, as `simulate broccoli --variety <name>` does (uk, spain, random, random-wide).
inline sim::BroccoliSimConfig sim_preset(const std::string& name) {
  sim::BroccoliSimConfig c;
  const auto path = testing::source_dir() / "configs" / ("sim-broccoli-" + name + ".yaml");
  apply_config(c, io::load_config_map(path), path.string());
  c.validate(path.string());
  return c;
}

/// Simulator config of the `spain` variety: configs/sim-broccoli-spain.yaml applied to the
/// defaults (= the `uk` preset), as `simulate broccoli --variety spain` does.
inline sim::BroccoliSimConfig spain_config() {
  sim::BroccoliSimConfig c;
  const auto path = testing::source_dir() / "configs" / "sim-broccoli-spain.yaml";
  apply_config(c, io::load_config_map(path), path.string());
  return c;
}

inline std::vector<RgbdFrame> simulate(const sim::BroccoliSimConfig& cfg, std::uint64_t seed, int frames) {
  sim::BroccoliSimulator s(cfg, seed, frames);
  std::vector<RgbdFrame> out;
  for (int i = 0; i < frames; ++i) out.push_back(s.render(i));
  return out;
}

}  // namespace cropsight::testdata
