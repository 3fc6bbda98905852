#pragma once
// The options of `cropsight train broccoli` and the steps its command runs: the training
// configuration (preset, --set and the flags that override it), the labelled sequences into the
// dataset, the grid search and the size fit, each with its progress lines.
#include <map>
#include <memory>
#include <string>
#include <utility>

#include "cli_common.hpp"
#include "cropsight/learning/grid_search.hpp"
#include "cropsight/pipeline/broccoli/training.hpp"

namespace cropsight::cli::train_broccoli_cmd {

struct TrainOptions {
  CommonOptions common;
  std::string data, pipeline, features, classifier, out;
  bool grid_search = false, fit_size_bias = false;
  bool quiet = false, force = false;
};

/// defaults ← preset ← --set ← explicit flags; keys "grid.*" configure the grid search. Throws
/// Error naming the key.
std::pair<pipeline::broccoli::Config, learning::GridSearchConfig> train_configs(const TrainOptions& o);

/// Adds every frame of the --data sequences to `builder`; returns the provenance the model file
/// records (data, seeds, varieties, frames). Throws Error(sequence, ...) for one without labels.
std::map<std::string, std::string> add_sequences(const TrainOptions& o, pipeline::broccoli::DatasetBuilder& builder);

/// The cross-validated grid search: sets cfg.classifier to the best point, returns its figures.
nlohmann::json grid_search(const TrainOptions& o, const learning::Dataset& data, const learning::GridSearchConfig& grid,
                           pipeline::broccoli::DetectorConfig& cfg);

/// The model's size correction, fitted on its own training passes and recorded in its config block
/// (pipeline/broccoli/size_calibration.hpp), so that every command sizes with it. Returns the values.
nlohmann::json fit_sizes(const TrainOptions& o, const pipeline::broccoli::Config& full,
                         const std::shared_ptr<learning::Model>& model);

}  // namespace cropsight::cli::train_broccoli_cmd
