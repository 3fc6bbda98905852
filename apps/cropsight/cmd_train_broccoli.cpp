// cropsight train broccoli: clusters every frame of labelled sequences with the chosen pipeline,
// labels clusters by the majority rule (pipeline/broccoli_truth.hpp), trains the classifier
// (optionally after a cross-validated grid search), optionally fits its size correction and writes
// one model file.
#include <cstdio>
#include <optional>

#include "broccoli_cli.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "train_broccoli_options.hpp"

namespace cropsight::cli {

namespace train_broccoli_cmd {
void run(const TrainOptions& o) {
  std::vector<std::string> inputs = training_sequences(o);
  inputs.push_back(o.common.config);
  if (o.fit_size_bias && !o.frames.empty())
    throw Error("--fit-size-bias", "fits the size correction on whole passes; not with --frame-list");
  if (!o.frames.empty()) parse_frame_list(o.frames);  // a bad list fails before the output is checked
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
  auto model = std::make_shared<learning::Model>(pipeline::broccoli::train_model(data, cfg, full.truth, provenance));
  nlohmann::json fit_json;
  if (o.fit_size_bias) fit_json = fit_sizes(o, full, model);
  learning::save_model(o.out, *model);
  const double secs = clock.seconds();

  nlohmann::json j{{"model", o.out},
                   {"pipeline", config_name(cfg.pipeline)},
                   {"features", cfg.features},
                   {"feature_dim", data.dim},
                   {"classifier", cfg.classifier.type},
                   {"frames", builder.frames()},
                   {"samples", data.size()},
                   {"positives", data.positives()},
                   {"model_size", model->classifier->model_size()},
                   {"seconds", json_number(secs)}};
  if (o.grid_search) j["grid_search"] = grid_json;
  if (o.fit_size_bias) j["size_correction"] = fit_json;
  if (o.common.json) {
    print_json(j);
  } else {
    std::printf("trained %s (%s, %s, %s) on %ld frames: %zu clusters, %zu heads; %zu %s; wrote %s (%.1f s)\n",
                cfg.classifier.type.c_str(), config_name(cfg.pipeline).c_str(), cfg.features.c_str(), o.data.c_str(),
                builder.frames(), data.size(), data.positives(), model->classifier->model_size(),
                cfg.classifier.type == "knn" ? "samples" : "support vectors", o.out.c_str(), secs);
  }
}
}  // namespace train_broccoli_cmd

void add_train_broccoli(CLI::App& train) {
  using namespace train_broccoli_cmd;
  auto o = std::make_shared<TrainOptions>();
  auto* cmd = train.add_subcommand("broccoli", "Train a broccoli head classifier on labelled sequences");
  cmd->add_option("--data", o->data, "Sequence directories, comma separated")->required();
  cmd->add_option("--frame-list", o->frames,
                  "Only these frames (comma list of 0-based indices) of each --data sequence, e.g. those "
                  "`suggest` chose");
  cmd->add_option("--extra-data", o->extra_data,
                  "Sequences trained on whole next to --data's frames (e.g. the general model's passes)");
  cmd->add_option("--pipeline", o->pipeline, "oes | org | fec (default: preset or oes)");
  cmd->add_option("--features", o->features, "Comma list of vfh, va, geom, cvfh (default: preset or vfh)");
  cmd->add_option("--classifier", o->classifier, "svm-rbf | svm-linear | knn (default: preset or svm-rbf)");
  cmd->add_option("--out", o->out, "Model file to write (JSON)")->required();
  add_force_flag(cmd, o->force);
  cmd->add_flag("--grid-search", o->grid_search,
                "5-fold stratified CV grid search over C (and gamma); keys grid.* via --set");
  cmd->add_flag("--fit-size-bias", o->fit_size_bias,
                "Fit the size correction on the training passes (tracking on) and record it in the model");
  cmd->add_flag("--quiet", o->quiet, "No progress lines");
  add_config_options(cmd, o->common);
  add_json_flag(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
