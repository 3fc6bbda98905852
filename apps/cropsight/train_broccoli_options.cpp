#include "train_broccoli_options.hpp"

#include <algorithm>
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

// The --frame-list list: ascending, without repeats.
std::vector<int> parse_frame_list(const std::string& text) {
  std::vector<int> frames;
  for (const auto& part : split_list(text, "--frame-list")) {
    std::size_t used = 0;
    int value = -1;
    try {
      value = std::stoi(part, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != part.size() || value < 0)
      throw Error("--frame-list", "'" + part + "' is not a frame index (a comma list of integers >= 0)");
    frames.push_back(value);
  }
  std::sort(frames.begin(), frames.end());
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  return frames;
}

// Adds the frames `chosen` (every frame when empty) of the sequence `dir` to `builder`.
void add_sequence(const TrainOptions& o, const std::string& dir, const std::vector<int>& chosen,
                  pipeline::broccoli::DatasetBuilder& builder, std::string& seeds, std::string& varieties) {
  io::SequenceReader reader(dir);
  if (!reader.info().has_labels) throw Error(dir, "sequence has no labels/ (training needs ground truth)");
  if (!chosen.empty() && chosen.back() >= reader.size())
    throw Error("--frame-list", "frame " + std::to_string(chosen.back()) + " is past the end of " + dir + " (" +
                                    std::to_string(reader.size()) + " frames)");
  const auto& attrs = reader.groundtruth().attributes;
  auto attr = [&](const char* k) { return attrs.count(k) ? attrs.at(k) : std::string("?"); };
  seeds += (seeds.empty() ? "" : ",") + attr("seed");
  varieties += (varieties.empty() ? "" : ",") + attr("variety");
  // The --frame-list frames, or those labels/ holds: every frame, or the ones labelled.csv lists
  // in a partly labelled pass (the studio writes such passes).
  const std::vector<int>& frames = chosen.empty() ? reader.info().labelled_frames : chosen;
  for (int f : chosen)
    if (!reader.info().labelled(f))
      throw Error("--frame-list", "frame " + std::to_string(f) + " of " + dir + " has no label image (labelled.csv)");
  Progress progress("train broccoli: " + dir, long(frames.size()), o.quiet || o.common.json);
  for (std::size_t k = 0; k < frames.size(); ++k) {
    builder.add_frame(reader.read(frames[k]));
    progress.update(long(k) + 1);
  }
  progress.finish();
}

// Adds the chosen frames of the --data sequences and every frame of --extra-data to `builder`;
// returns the provenance the model file records.
std::map<std::string, std::string> add_sequences(const TrainOptions& o, pipeline::broccoli::DatasetBuilder& builder) {
  std::string seeds, varieties;
  const std::vector<int> chosen = o.frames.empty() ? std::vector<int>{} : parse_frame_list(o.frames);
  for (const auto& dir : split_list(o.data, "--data")) add_sequence(o, dir, chosen, builder, seeds, varieties);
  if (!o.extra_data.empty())
    for (const auto& dir : split_list(o.extra_data, "--extra-data"))
      add_sequence(o, dir, {}, builder, seeds, varieties);
  std::map<std::string, std::string> provenance{
      {"data", o.data}, {"seeds", seeds}, {"varieties", varieties}, {"frames", std::to_string(builder.frames())}};
  if (!o.frames.empty()) provenance["chosen_frames"] = o.frames;
  if (!o.extra_data.empty()) provenance["extra_data"] = o.extra_data;
  return provenance;
}

// Every sequence trained on: --data's, then --extra-data's.
std::vector<std::string> training_sequences(const TrainOptions& o) {
  std::vector<std::string> all = split_list(o.data, "--data");
  if (!o.extra_data.empty())
    for (auto& dir : split_list(o.extra_data, "--extra-data")) all.push_back(std::move(dir));
  return all;
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
      model, full, training_sequences(o), [&](const std::string& dir, int done, int total) {
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
