// cropsight train broccoli: clusters every frame of labelled sequences with the chosen pipeline,
// labels clusters by the majority rule (pipeline/broccoli_truth.hpp), trains the classifier
// (optionally after a cross-validated grid search) and writes one model file.
#include <cstdio>
#include <optional>

#include "broccoli_cli.hpp"
#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/learning/grid_search.hpp"
#include "cropsight/pipeline/broccoli/training.hpp"

namespace cropsight::cli {

namespace train_broccoli_cmd {
struct TrainOptions {
  CommonOptions common;
  std::string data, pipeline, features, classifier, out;
  bool grid_search = false;
  bool quiet = false, force = false;
};

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
      builder.add_frame(reader.read(i));
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

void run(const TrainOptions& o) {
  std::vector<std::string> inputs = split_list(o.data, "--data");
  inputs.push_back(o.common.config);
  io::check_output_file(o.out, output_policy("train broccoli", o.force, inputs));  // before minutes of training
  auto [full, grid] = train_configs(o);
  pipeline::broccoli::DetectorConfig& cfg = full.detector;
  pipeline::broccoli::DatasetBuilder builder(cfg, full.truth);
  const Stopwatch clock;
  std::map<std::string, std::string> provenance = add_sequences(o, builder);
  const auto& data = builder.dataset();
  if (data.positives() == 0 || data.negatives() == 0)
    throw Error(o.data, "the clusters of these sequences are all of one class (" + std::to_string(data.positives()) +
                            " heads, " + std::to_string(data.negatives()) + " others); cannot train");
  nlohmann::json grid_json;
  if (o.grid_search) {
    grid_json = grid_search(o, data, grid, cfg);
    provenance["grid_search"] = grid_json.dump();
  }
  const learning::Model model = pipeline::broccoli::train_model(data, cfg, full.truth, provenance);
  learning::save_model(o.out, model);
  const double secs = clock.seconds();

  nlohmann::json j{{"model", o.out},
                   {"pipeline", config_name(cfg.pipeline)},
                   {"features", cfg.features},
                   {"feature_dim", data.dim},
                   {"classifier", cfg.classifier.type},
                   {"frames", builder.frames()},
                   {"samples", data.size()},
                   {"positives", data.positives()},
                   {"model_size", model.classifier->model_size()},
                   {"seconds", json_number(secs)}};
  if (o.grid_search) j["grid_search"] = grid_json;
  if (o.common.json) {
    print_json(j);
  } else {
    std::printf("trained %s (%s, %s, %s) on %ld frames: %zu clusters, %zu heads; %zu %s; wrote %s (%.1f s)\n",
                cfg.classifier.type.c_str(), config_name(cfg.pipeline).c_str(), cfg.features.c_str(), o.data.c_str(),
                builder.frames(), data.size(), data.positives(), model.classifier->model_size(),
                cfg.classifier.type == "knn" ? "samples" : "support vectors", o.out.c_str(), secs);
  }
}
}  // namespace train_broccoli_cmd

void add_train_broccoli(CLI::App& train) {
  using namespace train_broccoli_cmd;
  auto o = std::make_shared<TrainOptions>();
  auto* cmd = train.add_subcommand("broccoli", "Train a broccoli head classifier on labelled sequences");
  cmd->add_option("--data", o->data, "Sequence directories, comma separated")->required();
  cmd->add_option("--pipeline", o->pipeline, "oes | org | fec (default: preset or oes)");
  cmd->add_option("--features", o->features, "Comma list of vfh, va, geom, cvfh (default: preset or vfh)");
  cmd->add_option("--classifier", o->classifier, "svm-rbf | svm-linear | knn (default: preset or svm-rbf)");
  cmd->add_option("--out", o->out, "Model file to write (JSON)")->required();
  add_force_flag(cmd, o->force);
  cmd->add_flag("--grid-search", o->grid_search,
                "5-fold stratified CV grid search over C (and gamma); keys grid.* via --set");
  cmd->add_flag("--quiet", o->quiet, "No progress lines");
  add_config_options(cmd, o->common);
  add_json_flag(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
