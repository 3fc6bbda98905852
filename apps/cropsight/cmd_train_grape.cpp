// cropsight train grape: trains the grape bunch segmentation models on the dataset's
// labelled text clouds, with optional k-fold cross-validation by cloud.
//
//   cropsight train grape --clouds DIR [--model gbdt|pointresnet|pointnet2]
//       [--features xyz|xyzn|xyzrgb|xyzrgbn] --out MODEL [--epochs N]
//       [--val-fold k/K | --folds K] [--limit N] [--config PRESET] [--set key=value] [--json]
//
// --val-fold k/K trains on every fold but k and reports the metrics of fold k; --folds K runs
// all K folds and reports the pooled metrics, then (with --out) trains on every cloud.
// Without --model the model is the preset's `arch` (a network preset), else gbdt.
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/threads.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/pipeline/grape/cloud_files.hpp"
#include "cropsight/pipeline/grape/model.hpp"
#include "cropsight/pipeline/grape/training.hpp"
#include "cropsight/pipeline/grape/truth.hpp"
#include "grape_cli.hpp"
#include "train_grape_options.hpp"

namespace cropsight::cli {
namespace train_grape_cmd {
// Progress lines go to stderr, so that stdout holds only the result.
void progress(const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); }

void run(const TrainGrapeOptions& o) {
  if (o.data.empty()) throw Error("--clouds", "give the labelled clouds (a folder, files or a list)");
  check_train_grape_options(o);
  // Before minutes of training: the model and the checkpoint (which a rerun resumes from, so it
  // may exist) are outputs, never inputs.
  const io::OutputPolicy policy = output_policy("train grape", o.force, {o.data, o.common.config});
  if (!o.out.empty()) io::check_output_file(o.out, policy);
  if (!o.checkpoint.empty()) io::check_not_an_input(o.checkpoint, policy);
  const pipeline::grape::TrainConfig cfg = train_grape_config(o);
  const auto say = [&o](const std::string& line) {
    if (!o.quiet) progress(line);
  };
  auto files = pipeline::grape::list_cloud_files(o.data);
  if (o.limit_set && std::size_t(o.limit) < files.size()) files.resize(std::size_t(o.limit));
  const auto clouds = pipeline::grape::load_grape_clouds(files);
  nlohmann::json result = {{"model", cfg.model}, {"clouds", clouds.size()}};
  if (cfg.model != "gbdt") result["features"] = o.features;

  if (!o.val_fold.empty() || o.folds_set) {
    const pipeline::grape::FoldPlan plan = train_grape_fold_plan(o, clouds.size());
    const auto cv = pipeline::grape::cross_validate_grape(cfg, clouds, plan, say);
    result["validation"] = grape_evaluation_json(cv.pooled);
    result["validation"]["folds"] = plan.folds;
    result["validation"]["folds_run"] = plan.last - plan.first;
    result["validation"]["train_seconds"] = json_number(cv.train_seconds);
    if (!o.common.json) std::printf("held-out (k-fold by cloud):\n%s", cv.pooled.text().c_str());
    if (!o.val_fold.empty()) {
      result["out"] = o.out;
      if (o.common.json) print_json(result);
      return;
    }
  }
  if (!o.out.empty()) {
    const Stopwatch clock;
    pipeline::grape::train_grape_model(cfg, clouds, {}, o.out, [&](const std::string& line) { say("[all] " + line); });
    result["out"] = o.out;
    result["train_seconds"] = json_number(clock.seconds());
    if (!o.common.json)
      std::printf("trained on %zu clouds in %.1f s -> %s\n", clouds.size(), clock.seconds(), o.out.c_str());
  }
  if (o.common.json) print_json(result);
}
}  // namespace train_grape_cmd

void add_train_grape(CLI::App& train) {
  using namespace train_grape_cmd;
  auto o = std::make_shared<TrainGrapeOptions>();
  auto* cmd = train.add_subcommand("grape", "Train a grape bunch segmentation model (GBDT, PointResNet, PointNet++)");
  cmd->add_option("--clouds", o->data,
                  "Labelled clouds: a folder (directly or under points/), files or a comma-separated list; the "
                  "dataset's .txt, or .ply / .pcd with a label field");
  add_deprecated_option(cmd, "--data", o->data, "--clouds");
  cmd->add_option("--model", o->model,
                  "gbdt | pointresnet | pointnet2 (default: the --config preset's arch, else gbdt)");
  cmd->add_option("--features", o->features, "Network inputs: xyz | xyzn | xyzrgb | xyzrgbn");
  cmd->add_option("--out", o->out, "Model file to write (.json for gbdt, .pt for networks)");
  add_force_flag(cmd, o->force);
  cmd->add_flag("--quiet", o->quiet, "No progress lines");
  auto* epochs = cmd->add_option("--epochs", o->epochs, "Network training epochs, >= 1 (overrides the preset)");
  cmd->add_option("--val-fold", o->val_fold, "k/K: train without fold k and report its metrics");
  auto* folds = cmd->add_option("--folds", o->folds,
                                "Run K-fold (K >= 2) cross-validation by cloud, then train on all (with --out)");
  auto* limit = cmd->add_option("--limit", o->limit, "Use only the first N clouds, N >= 1 (quick runs)");
  auto* threads = cmd->add_option("--threads", o->threads,
                                  "Threads for XGBoost / libtorch / FPFH, 1.." + std::to_string(kMaxThreads) +
                                      " (default: the preset's, 2); overrides --config/--set");
  cmd->add_option("--checkpoint", o->checkpoint, "Network checkpoint written every epoch and resumed from");
  cmd->add_option("--split-seed", o->split_seed, "Seed of the fold split");
  add_json_flag(cmd, o->common);
  add_config_options(cmd, o->common);
  cmd->callback([o, epochs, folds, limit, threads] {
    o->epochs_set = epochs->count() > 0;
    o->folds_set = folds->count() > 0;
    o->limit_set = limit->count() > 0;
    o->threads_set = threads->count() > 0;
    run(*o);
  });
}

}  // namespace cropsight::cli
