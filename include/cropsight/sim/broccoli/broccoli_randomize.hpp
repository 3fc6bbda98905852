#pragma once
// Domain randomisation of the broccoli-field simulator (docs/simulator.md, "Randomised fields").
//
// A randomised sequence simulates one field drawn from the ranges of config.randomize: field
// layout (rows, spacings), plants (leaf shape family, count, size, tilt, droop, wavy margins,
// canopy height), heads (size window, dome, floret bumps, depth in the canopy, leaves over them),
// soil (roughness, clods, weeds), camera (height, tilt) and sensor (Kinect v2 ToF or stereo, and
// their noise, edge and dropout parameters). The draw uses its own random stream of the seed, so
// the same seed and config give the same field; the scene itself is then simulated exactly like
// a preset's, with exact ground truth.
#include <cstdint>
#include <string>

#include "cropsight/sim/broccoli/broccoli_config.hpp"

namespace cropsight::sim {

/// Leaf shape families a randomised sequence draws from (randomize.leaf_family_weights order).
enum class LeafFamily { pointed, broad, obovate };
const char* leaf_family_name(LeafFamily family);

/// `base` with its randomised values drawn from base.randomize from `seed` (randomize.enabled is
/// kept, so a drawn config reports where it came from); `base` itself when randomize is off.
/// `family` (optional) receives the drawn leaf family.
BroccoliSimConfig draw_randomized_config(const BroccoliSimConfig& base, std::uint64_t seed,
                                         LeafFamily* family = nullptr);

/// Throws Error(where, ...) when a randomize range is malformed ({min, max}, min <= max) or would
/// draw values the simulator rejects.
void validate_randomize(const SimRandomizeConfig& r, const std::string& where);

}  // namespace cropsight::sim
