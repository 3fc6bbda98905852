#pragma once
// The truth of a seedling pair rendered in memory (sim::simulate_seedling_pair) as the evaluator
// takes it, without a round trip through files. A test helper: the library's pipeline does not
// depend on the simulator.
#include "cropsight/pipeline/seedling/truth.hpp"
#include "cropsight/sim/seedling/seedling_sim.hpp"

namespace cropsight::testing {

inline pipeline::seedling::Truth seedling_truth(const sim::SeedlingPair& p) {
  return {p.disparity, p.mask, p.envelope, p.plane_normal, p.plane_d};
}

}  // namespace cropsight::testing
