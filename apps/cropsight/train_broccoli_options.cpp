#include "train_broccoli_options.hpp"

#include <optional>

#include "cropsight/core/error.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/pipeline/broccoli/size_calibration.hpp"

namespace cropsight::cli::train_broccoli_cmd {

// defaults ← preset ← --set ← explicit flags; keys "grid.*" configure the grid search. The whole
// preset is one pipeline::broccoli::Config: sizing.* / tracking.* configure detect/eval --track, not
// training, and are checked all the same.
std::pair<pipeline::broccoli::Config, learning::GridSearchConfig> train_configs(const TrainOptions& o) {
  ConfigMap all = o.common.config_map();
  ConfigMap grid_keys, pipeline_keys;
  for (const auto& [k, v] : all) (k.rfind("grid.", 0) == 0 ? grid_keys : pipeline_keys)[k] = v;
  pipeline::broccoli::Config full;
  apply_config(full, pipeline_keys, o.common.config.empty() ? "--set" : o.common.config);
  learning::GridSearchConfig grid;
  apply_config(grid, grid_keys, "--set", "grid.");
  if (!o.pipeline.empty()) detail::parse_value("--pipeline", "pipeline", o.pipeline, full.detector.pipeline);
  if (!o.features.empty()) full.detector.features = o.features;
  if (!o.classifier.empty()) full.detector.classifier.type = o.classifier;
  full.validate("--pipeline/--features/--classifier");
  return {full, grid};
}

// Adds every frame of the --data sequences to `builder`; returns the provenance the model file
// records (data, seeds, varieties, frames).
std::map<std::string, std::string> add_sequences(const TrainOptions& o, pipeline::broccoli::DatasetBuilder& builder) {
  std::string seeds, varieties;
  for (const auto& dir : split_list(o.data, "--data")) {
    io::SequenceReader reader(dir);
    if (!reader.info().has_labels) throw Error(dir, "sequence has no labels/ (training needs ground truth)");
    const auto& attrs = reader.groundtruth().attributes;
    auto attr = [&](const char* k) { return attrs.count(k) ? attrs.at(k) : std::string("?"); };
    seeds += (seeds.empty() ? "" : ",") + attr("seed");
    varieties += (varieties.empty() ? "" : ",") + attr("variety");
    Progress progress("train broccoli: " + dir, reader.size(), o.quiet || o.common.json);
    for (int i = 0; i < reader.size(); ++i) {
      if (reader.info().labelled(i)) builder.add_frame(reader.read(i));  // a partly labelled pass (labelled.csv)
      progress.update(i + 1);
    }
    progress.finish();
  }
  return {{"data", o.data}, {"seeds", seeds}, {"varieties", varieties}, {"frames", std::to_string(builder.frames())}};
}

// The cross-validated grid search: sets cfg.classifier to the best point, returns its figures.
nlohmann::json grid_search(const TrainOptions& o, const learning::Dataset& data, const learning::GridSearchConfig& grid,
                           pipeline::broccoli::DetectorConfig& cfg) {
  // One line per grid point at most once a second: a full grid is ~100 × folds SVM trainings.
  std::optional<Progress> progress;
  const auto r =
      learning::grid_search(data, cfg.classifier, grid, "grid search", [&](std::size_t done, std::size_t total) {
        if (!progress)
          progress.emplace("grid search (" + std::to_string(grid.folds) + "-fold CV per point)", long(total),
                           o.quiet || o.common.json);
        progress->update(long(done));
        if (done == total) progress->finish();
      });
  cfg.classifier = r.params;
  return {{"best_c", r.best.c},       {"best_gamma", r.best.gamma}, {"cv_accuracy", r.best.accuracy},
          {"cv_kappa", r.best.kappa}, {"points", r.points.size()},  {"folds", grid.folds},
          {"metric", grid.metric}};
}

// The model's size correction, fitted on its own training passes and recorded in its config block
// (pipeline/broccoli/size_calibration.hpp), so that every command sizes with it.
nlohmann::json fit_sizes(const TrainOptions& o, const pipeline::broccoli::Config& full,
                         const std::shared_ptr<learning::Model>& model) {
  std::optional<Progress> progress;
  const auto fit = pipeline::broccoli::fit_size_correction(
      model, full, split_list(o.data, "--data"), [&](const std::string& dir, int done, int total) {
        if (done == 1) progress.emplace("size fit: " + dir, total, o.quiet || o.common.json);
        progress->update(done);
        if (done == total) progress->finish();
      });
  nlohmann::json j;
  for (const auto& [key, value] : pipeline::broccoli::size_correction_values(fit)) {
    model->info.config[key] = value;
    j[key] = std::stod(value);
  }
  return j;
}

}  // namespace cropsight::cli::train_broccoli_cmd
