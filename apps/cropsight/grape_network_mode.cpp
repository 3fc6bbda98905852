#include "grape_network_mode.hpp"

#include "cropsight/core/error.hpp"

namespace cropsight::cli {

void GrapeNetworkMode::add_options(CLI::App* cmd) {
  cmd->add_flag("--sampled", sampled,
                "Networks: the paper's mode, one pass on num_points samples, labels carried back to the other points "
                "(--carry-k; default: a prediction for every point)");
  cmd->add_option("--sampling", sampling, "With --sampled: random (as in training, default) or fps");
  cmd->add_option("--carry-k", carry_k,
                  "With --sampled: samples voting for each other point, weighted by distance and colour (default 4; 1 "
                  "= nearest, the paper)");
  cmd->add_option("--votes", votes,
                  "Networks: N passes rotated about the vertical axis by 360/N degrees each, as test-time "
                  "augmentation (every-point mode: N covers, class probabilities averaged; --sampled: N samples, "
                  "probabilities carried back and summed); N times the time (default 1)");
}

void GrapeNetworkMode::apply(pipeline::GrapeModel& model) const {
  if (sampling != "random" && sampling != "fps")
    throw Error("--sampling", "expected random or fps, got '" + sampling + "'");
  model.set_sampled(sampled, sampling == "fps", carry_k);
  model.set_votes(votes);
}

}  // namespace cropsight::cli
