#include "train_grape_options.hpp"

#include <filesystem>

#include "cropsight/core/error.hpp"
#include "cropsight/core/threads.hpp"
#include "cropsight/pipeline/grape/model.hpp"

namespace cropsight::cli {
namespace fs = std::filesystem;

void check_train_grape_options(const TrainGrapeOptions& o) {
  if (o.threads_set) check_thread_count(o.threads, "--threads");
  if (o.epochs_set && o.epochs < 1) throw Error("--epochs", "must be at least 1, got " + std::to_string(o.epochs));
  if (o.limit_set && o.limit < 1) throw Error("--limit", "must be at least 1, got " + std::to_string(o.limit));
  if (o.folds_set && o.folds < 2) throw Error("--folds", "must be at least 2, got " + std::to_string(o.folds));
  if (!o.val_fold.empty() && o.folds_set) throw Error("--folds", "use either --folds or --val-fold");
  if (o.out.empty() && !o.folds_set) throw Error("--out", "required unless --folds is given");
  // The model is written only after training: a folder there must fail now, not in an hour.
  if (!o.out.empty() && fs::is_directory(o.out)) throw Error(o.out, "is a directory, expected a model file name");
  if (!o.checkpoint.empty()) {
    if (fs::exists(o.checkpoint) && !fs::is_regular_file(o.checkpoint))
      throw Error(o.checkpoint, "is not a checkpoint file (a directory?)");
    // Every fold would resume from the previous fold's checkpoint (and train nothing).
    if (o.folds_set) throw Error("--checkpoint", "only for a single training run, not with --folds");
  }
}

pipeline::grape::TrainConfig train_grape_config(const TrainGrapeOptions& o) {
  pipeline::grape::TrainConfig c;
  c.model = o.model;
  ConfigMap cfg_map;
  if (c.model.empty() && !o.common.config.empty()) {
    cfg_map = o.common.config_map();
    const auto arch = cfg_map.find("arch");
    c.model = arch != cfg_map.end() ? arch->second : "gbdt";
  }
  if (c.model.empty()) c.model = "gbdt";
  const std::string& model = c.model;
  if (model != "gbdt" && model != "pointresnet" && model != "pointnet2")
    throw Error("--model", "expected gbdt, pointresnet or pointnet2, got '" + model + "'");
  if (model != "gbdt") nn::feature_channels(o.features);
  if (!o.checkpoint.empty() && model == "gbdt") throw Error("--checkpoint", "only for network models");
  if (cfg_map.empty()) cfg_map = o.common.config_map(o.common.config.empty() ? "grape-" + model : "");
  if (model == "gbdt" && cfg_map.count("arch"))
    throw Error("--model", "gbdt, but --config/--set is for the " + cfg_map.at("arch") + " network (give --model " +
                               cfg_map.at("arch") + " or a grape-gbdt preset)");
  if (model == "gbdt") {
    c.gbdt.gbdt.nthread = c.gbdt.features.threads = o.eval_threads();
    apply_config(c.gbdt, cfg_map, "--config/--set");
    if (o.threads_set) c.gbdt.gbdt.nthread = c.gbdt.features.threads = o.threads;
    c.gbdt.validate("--config/--set");
    return c;
  }
  nn::PointNetConfig& cfg = c.net;
  cfg.arch = model;
  cfg.threads = o.eval_threads();
  apply_config(cfg, cfg_map, "--config/--set");
  if (o.threads_set) cfg.threads = o.threads;  // the presets say threads: 2; --threads must still win
  cfg.arch = model;
  cfg.features = o.features;
  if (o.epochs_set) cfg.epochs = o.epochs;
  cfg.checkpoint = o.checkpoint;
  cfg.validate("--config/--set");
  return c;
}

pipeline::grape::FoldPlan train_grape_fold_plan(const TrainGrapeOptions& o, std::size_t clouds) {
  pipeline::grape::FoldPlan plan;
  plan.folds = o.folds, plan.first = 0, plan.last = o.folds;
  if (!o.val_fold.empty()) {
    const auto [k, K] = pipeline::grape::parse_fold(o.val_fold, "--val-fold");
    plan.folds = K, plan.first = k, plan.last = k + 1;
    plan.keep_model = o.out;
  }
  if (std::size_t(plan.folds) > clouds)
    throw Error(o.val_fold.empty() ? "--folds" : "--val-fold",
                std::to_string(plan.folds) + " folds need at least " + std::to_string(plan.folds) + " clouds, " +
                    o.data + " has " + std::to_string(clouds) + (o.limit_set ? " (after --limit)" : ""));
  plan.split_seed = o.split_seed;
  plan.eval_threads = o.eval_threads();
  return plan;
}

}  // namespace cropsight::cli
