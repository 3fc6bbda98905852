// cropsight as a library, end to end: render simulated stereo pairs of broccoli seedlings among
// weeds, recognise the seedling in each with the seedling pipeline built from a shipped preset,
// and score it against the simulator's exact ground truth - the headline figure of
// docs/pipelines/broccoli-seedlings.md, with no CLI and no files.
//
//   example_seedling_recognise [PRESET [SEED [PAIRS]]]     (default: seedling 4711 30)
//
// With the defaults it reproduces the held-out figure the docs report for the fast preset on seed
// 4711 (30 pairs): recognition 100.0 %, sensitivity 90.8 %, envelope volume ratio 99.9 %; ctest runs
// it on the first 8 pairs (100.0 %, 91.7 %, 99.8 %). Rendering takes most of the time, ~0.6 s of
// CPU a pair. (The docs' figures went through `simulate seedling`'s files, whose disparity.png
// stores the true disparity in 1/256 px; in memory the truth is exact, which moves the scores by
// at most 0.1 point: on the 8 pairs sensitivity 91.6 % from the files.)
#include <cstdio>
#include <cstdlib>
#include <string>

#include "cropsight/core/error.hpp"
#include "cropsight/pipeline/seedling/eval.hpp"
#include "cropsight/pipeline/seedling/make_pipeline.hpp"
#include "cropsight/pipeline/seedling/pipeline.hpp"
#include "cropsight/sim/seedling/seedling_sim.hpp"

int main(int argc, char** argv) {
  using namespace cropsight;
  const std::string preset = argc > 1 ? argv[1] : "seedling";
  const long seed = argc > 2 ? std::strtol(argv[2], nullptr, 10) : 4711;
  const long pairs = argc > 3 ? std::strtol(argv[3], nullptr, 10) : 30;
  if (argc > 4 || seed < 0 || pairs < 1 || pairs > sim::kMaxSeedlingPairs) {
    std::fprintf(stderr, "usage: %s [PRESET [SEED >= 0 [PAIRS 1..%d]]]\n", argv[0], sim::kMaxSeedlingPairs);
    return 2;
  }
  try {
    // The pipeline composes every step from the one config of the preset (configs/<preset>.yaml).
    const auto built = pipeline::seedling::make_pipeline({.preset = preset});
    const pipeline::seedling::Pipeline& seedlings = *built;
    const sim::SeedlingSimConfig scenes;  // the simulator's defaults: what `simulate seedling` renders
    const stereo::RectifiedGeometry geometry = sim::rectified_geometry(scenes.rig());
    pipeline::seedling::Evaluator evaluator(seedlings.config().gmm);
    for (int k = 0; k < int(pairs); ++k) {
      const sim::SeedlingPair pair = sim::simulate_seedling_pair(scenes, std::uint64_t(seed), k);
      const pipeline::seedling::FrameResult det = seedlings.process(pair.left, pair.right, geometry);
      // The simulator renders the truth beside the pair; a recorded data set reads it (read_truth).
      const pipeline::seedling::Truth truth{pair.disparity, pair.mask, pair.envelope, pair.plane_normal, pair.plane_d};
      const auto& row = evaluator.add("pair_" + std::to_string(k), det, truth, geometry);
      std::printf("pair %d: %s, %.0f x %.0f x %.0f mm, IoU %.3f, %.1f ms\n", k, det.found ? "seedling" : "nothing",
                  1e3 * det.envelope.length, 1e3 * det.envelope.width, 1e3 * det.envelope.height, row.score.iou,
                  row.ms);
    }
    const pipeline::seedling::Figures e = evaluator.figures();
    std::printf(
        "%s, seed %ld, %d pairs: recognition %.1f %%, sensitivity %.1f %%, volume ratio %.1f %%, %.1f ms a pair\n",
        preset.c_str(), seed, e.pairs, 100 * e.recognition_rate, 100 * e.sensitivity, 100 * e.volume_ratio, e.ms_total);
    return 0;
  } catch (const Error& e) {  // every bad input (preset file, value) is an Error naming it
    std::fprintf(stderr, "example_seedling_recognise: %s\n", e.what());
    return 2;
  }
}
