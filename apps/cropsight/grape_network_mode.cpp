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
  cmd->add_option("--ensemble", ensemble,
                  "A second model (network or GBDT, default settings) whose per-point class probabilities are mixed "
                  "with this model's; the label is the argmax of the mix");
  cmd->add_option("--ensemble-weight", ensemble_weight, "With --ensemble: the second model's share (default 0.5)");
}

void GrapeNetworkMode::apply(pipeline::GrapeModel& model, int threads) const {
  if (sampling != "random" && sampling != "fps")
    throw Error("--sampling", "expected random or fps, got '" + sampling + "'");
  model.set_sampled(sampled, sampling == "fps", carry_k);
  model.set_votes(votes);
  if (!ensemble.empty())
    model.set_ensemble(std::make_shared<const pipeline::GrapeModel>(pipeline::GrapeModel::load(ensemble, threads)),
                       ensemble_weight);
  else if (ensemble_weight != 0.5)
    throw Error("--ensemble-weight", "needs --ensemble");
}

void GrapeNetworkMode::describe(nlohmann::json& j) const {
  j["votes"] = votes;
  if (!ensemble.empty()) {
    j["ensemble"] = ensemble;
    j["ensemble_weight"] = ensemble_weight;
  }
}

}  // namespace cropsight::cli
