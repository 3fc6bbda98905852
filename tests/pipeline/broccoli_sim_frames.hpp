#pragma once
// Simulated broccoli frames for the pipeline tests (rendered in-process by the sim module).
#include <vector>

#include "cropsight/core/rgbd_frame.hpp"
#include "cropsight/sim/broccoli_sim.hpp"

namespace cropsight::testdata {

/// Simulator config of the `spain` variety (what configs/sim-broccoli-spain.yaml changes).
inline sim::BroccoliSimConfig spain_config() {
  sim::BroccoliSimConfig c;
  c.field.variety = "spain";
  c.camera.height_m = 1.40;
  c.field.rows_under_camera = 1;
  c.field.row_spacing_m = 0.90;
  c.field.in_row_spacing_m = 0.30;
  return c;
}

inline std::vector<RgbdFrame> simulate(const sim::BroccoliSimConfig& cfg, std::uint64_t seed, int frames) {
  sim::BroccoliSimulator s(cfg, seed, frames);
  std::vector<RgbdFrame> out;
  for (int i = 0; i < frames; ++i) out.push_back(s.render(i));
  return out;
}

}  // namespace cropsight::testdata
