#pragma once
// The options of `cropsight train broccoli` and the steps its command runs: the training
// configuration (preset, --set and the flags that override it), the labelled sequences into the
// dataset, the grid search and the size fit, each with its progress lines.
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cli_common.hpp"
#include "cropsight/learning/grid_search.hpp"
#include "cropsight/pipeline/broccoli/config.hpp"
#include "cropsight/pipeline/broccoli/training.hpp"

namespace cropsight::cli::train_broccoli_cmd {

struct TrainOptions {
  CommonOptions common;
  std::string data, pipeline, features, classifier, out;
  std::string frames;      ///< --frame-list: only these frame indices of each --data sequence ("" = all)
  std::string extra_data;  ///< --extra-data: sequences trained on whole, next to --data's frames
  bool grid_search = false, fit_size_bias = false;
  bool quiet = false, force = false;
};

/// defaults ← preset ← --set ← explicit flags; keys "grid.*" configure the grid search. Throws
/// Error naming the key.
std::pair<pipeline::broccoli::Config, learning::GridSearchConfig> train_configs(const TrainOptions& o);

/// Adds the frames of the --data sequences (those of --frame-list, or every one) and every frame of the
/// --extra-data sequences to `builder`; returns the provenance the model file records (data, seeds,
/// varieties, frames, chosen_frames). Throws Error(sequence, ...) for one without labels and
/// Error("--frame-list", ...) for an index outside a sequence.
std::map<std::string, std::string> add_sequences(const TrainOptions& o, pipeline::broccoli::DatasetBuilder& builder);

/// The cross-validated grid search: sets cfg.classifier to the best point, returns its figures.
nlohmann::json grid_search(const TrainOptions& o, const learning::Dataset& data, const learning::GridSearchConfig& grid,
                           pipeline::broccoli::DetectorConfig& cfg);

/// Every sequence trained on: --data's, then --extra-data's.
std::vector<std::string> training_sequences(const TrainOptions& o);

/// The --frame-list list: ascending, without repeats; throws Error("--frame-list", ...) for a bad entry.
std::vector<int> parse_frame_list(const std::string& text);

/// The model's size correction, fitted on its own training passes and recorded in its config block
/// (pipeline/broccoli/size_calibration.hpp), so that every command sizes with it. Returns the values.
nlohmann::json fit_sizes(const TrainOptions& o, const pipeline::broccoli::Config& full,
                         const std::shared_ptr<learning::Model>& model);

}  // namespace cropsight::cli::train_broccoli_cmd
