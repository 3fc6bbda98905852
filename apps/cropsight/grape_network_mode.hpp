#pragma once
// The network-mode options that `eval grape` and `segment grape` share: every point (default) or
// the paper's one sampled pass with --sampling and --carry-k (pipeline::GrapeModel::set_sampled),
// and --votes (test-time augmentation of the every-point mode, GrapeModel::set_votes).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "cropsight/pipeline/grape_model.hpp"

namespace cropsight::cli {

struct GrapeNetworkMode {
  bool sampled = false;
  std::string sampling = "random";
  int carry_k = 4;               // the fast GBDT's colour-guided vote; 1 = the paper's nearest neighbour
  int votes = 1;                 // every-point mode: rotated covers of the cloud, probabilities averaged
  std::string ensemble;          // a second model whose probabilities are mixed in
  double ensemble_weight = 0.5;  // its share

  void add_options(CLI::App* cmd);
  /// Checks --sampling and sets the mode on `model` (throws Error for a bad value, a GBDT model
  /// with --sampled, or --carry-k < 1).
  void apply(pipeline::GrapeModel& model, int threads = 2) const;
  const char* name() const { return sampled ? "sampled" : "every-point"; }
  /// Adds "votes" and, with an ensemble, "ensemble" and "ensemble_weight" to a JSON report.
  void describe(nlohmann::json& j) const;
};

}  // namespace cropsight::cli
