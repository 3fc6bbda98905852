// cropsight train grape: trains the grape bunch segmentation models (issue 6) on the dataset's
// labelled text clouds, with optional k-fold cross-validation by cloud.
//
//   cropsight train grape --data DIR [--model gbdt|pointresnet|pointnet2]
//       [--features xyz|xyzn|xyzrgb|xyzrgbn] --out MODEL [--epochs N]
//       [--val-fold k/K | --folds K] [--limit N] [--config PRESET] [--set key=value] [--json]
//
// --val-fold k/K trains on every fold but k and reports the metrics of fold k; --folds K runs
// all K folds and reports the pooled metrics, then (with --out) trains on every cloud.
// Without --model the model is the preset's `arch` (a network preset), else gbdt.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/core/threads.hpp"
#include "cropsight/io/grape_text.hpp"
#include "cropsight/nn/point_segmenter.hpp"
#include "cropsight/pipeline/grape/grape_eval.hpp"
#include "cropsight/pipeline/grape/grape_gbdt.hpp"
#include "cropsight/pipeline/grape/grape_model.hpp"

namespace cropsight::cli {
namespace {
namespace fs = std::filesystem;

struct TrainGrapeOptions {
  CommonOptions common;
  std::string data, model, features = "xyzrgbn", out, val_fold, checkpoint;  // model "": from the preset
  int epochs = 0, folds = 0, limit = 0;  // meaningful only when given (the *_set flags)
  bool epochs_set = false, folds_set = false, limit_set = false, threads_set = false;
  int threads = 0;  // unset: the preset's value (2); an explicit --threads wins over --config/--set
  int eval_threads() const { return threads_set ? threads : 2; }
  std::uint64_t split_seed = 1;
};

// Both kinds' configurations, built and validated before any cloud is loaded, so that a bad
// --set value fails at once and names its key (not deep inside XGBoost or libtorch).
struct TrainConfigs {
  pipeline::GrapeGbdtConfig gbdt;
  nn::PointNetConfig net;
};

TrainConfigs make_configs(const TrainGrapeOptions& o, const std::string& model, const ConfigMap& cfg_map) {
  TrainConfigs c;
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

// Removes a fold's temporary model however its fold ends (an exception included).
struct RemoveOnExit {
  fs::path path;
  ~RemoveOnExit() {
    std::error_code ec;
    if (!path.empty()) fs::remove(path, ec);
  }
};

double now_s() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

// Trains one model on `train` (validating networks on `val`) and writes it to `out`.
void train_one(const std::string& model, const TrainConfigs& cfgs, const std::vector<Cloud>& train,
               const std::vector<Cloud>& val, const fs::path& out, const std::string& tag) {
  if (model == "gbdt") {
    auto m = pipeline::train_grape_gbdt(
        train, cfgs.gbdt, [&](const std::string& line) { std::fprintf(stderr, "%s%s\n", tag.c_str(), line.c_str()); });
    m.save(out);
    return;
  }
  const nn::PointNetConfig& cfg = cfgs.net;
  nn::PointSegmenter net(cfg);
  std::fprintf(stderr, "%s%s, features %s, %zu parameters, %zu training clouds, %d thread%s\n", tag.c_str(),
               cfg.arch.c_str(), cfg.features.c_str(), net.parameter_count(), train.size(), cfg.threads,
               cfg.threads == 1 ? "" : "s");
  net.train(train, val, [&](const nn::EpochLog& l) {
    if (l.val_miou >= 0)
      std::fprintf(stderr, "%sepoch %d/%d  loss %.4f  train acc %.4f  val mIoU %.4f  lr %.2e  %.1f s\n", tag.c_str(),
                   l.epoch, cfg.epochs, l.loss, l.train_acc, l.val_miou, l.lr, l.seconds);
    else
      std::fprintf(stderr, "%sepoch %d/%d  loss %.4f  train acc %.4f  lr %.2e  %.1f s\n", tag.c_str(), l.epoch,
                   cfg.epochs, l.loss, l.train_acc, l.lr, l.seconds);
    std::fflush(stderr);
  });
  net.save(out);
}

void run(const TrainGrapeOptions& o) {
  // Options first, each named: 0 or a negative count used to mean "the preset's" or "all"
  // without a word.
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

  // A preset names its network (`arch`); without --model that decides, else gbdt.
  std::string model = o.model;
  ConfigMap cfg_map;
  if (model.empty() && !o.common.config.empty()) {
    cfg_map = o.common.config_map();
    const auto arch = cfg_map.find("arch");
    model = arch != cfg_map.end() ? arch->second : "gbdt";
  }
  if (model.empty()) model = "gbdt";
  if (model != "gbdt" && model != "pointresnet" && model != "pointnet2")
    throw Error("--model", "expected gbdt, pointresnet or pointnet2, got '" + model + "'");
  if (model != "gbdt") nn::feature_channels(o.features);
  if (!o.checkpoint.empty() && model == "gbdt") throw Error("--checkpoint", "only for network models");
  if (cfg_map.empty()) cfg_map = o.common.config_map(o.common.config.empty() ? "grape-" + model : "");
  if (model == "gbdt" && cfg_map.count("arch"))
    throw Error("--model", "gbdt, but --config/--set is for the " + cfg_map.at("arch") + " network (give --model " +
                               cfg_map.at("arch") + " or a grape-gbdt preset)");
  const TrainConfigs cfgs = make_configs(o, model, cfg_map);

  auto files = io::list_grape_clouds(o.data);
  if (o.limit_set && std::size_t(o.limit) < files.size()) files.resize(std::size_t(o.limit));
  const auto clouds = pipeline::load_grape_clouds(files);
  nlohmann::json result = {{"model", model}, {"clouds", clouds.size()}};
  if (model != "gbdt") result["features"] = o.features;

  auto split = [&](int k, int K, std::vector<Cloud>& tr, std::vector<Cloud>& va) {
    const auto fold = pipeline::grape_folds(clouds.size(), K, o.split_seed);
    for (std::size_t i = 0; i < clouds.size(); ++i) (fold[i] == k ? va : tr).push_back(clouds[i]);
  };

  if (!o.val_fold.empty() || o.folds_set) {
    int K = o.folds, first = 0, last = o.folds;
    if (!o.val_fold.empty()) {
      auto [k, KK] = pipeline::parse_fold(o.val_fold, "--val-fold");
      K = KK, first = k, last = k + 1;
    }
    // Folds are dealt round-robin: K <= clouds leaves none empty (an empty fold scored "nan").
    if (std::size_t(K) > clouds.size())
      throw Error(o.val_fold.empty() ? "--folds" : "--val-fold",
                  std::to_string(K) + " folds need at least " + std::to_string(K) + " clouds, " + o.data + " has " +
                      std::to_string(clouds.size()) + (o.limit_set ? " (after --limit)" : ""));
    pipeline::GrapeEvaluation pooled;
    double train_s = 0;
    for (int k = first; k < last; ++k) {
      std::vector<Cloud> tr, va;
      split(k, K, tr, va);
      const std::string tag = "[fold " + std::to_string(k + 1) + "/" + std::to_string(K) + "] ";
      const fs::path model_path =
          !o.val_fold.empty()
              ? fs::path(o.out)
              : fs::temp_directory_path() / ("cropsight-grape-fold-" + std::to_string(::getpid()) + "-" +
                                             std::to_string(k) + (model == "gbdt" ? ".json" : ".pt"));
      const RemoveOnExit fold_model{o.val_fold.empty() ? model_path : fs::path()};
      const double t0 = now_s();
      train_one(model, cfgs, tr, va, model_path, tag);
      train_s += now_s() - t0;
      const auto trained = pipeline::GrapeModel::load(model_path, o.eval_threads());
      const auto ev = pipeline::evaluate_grape(trained, va);
      std::fprintf(stderr, "%sheld-out: OAcc %.4f  mAcc %.4f  mIoU %.4f  (%zu clouds, %.1f ms/cloud, train %.0f s)\n",
                   tag.c_str(), ev.confusion.overall_accuracy(), ev.confusion.mean_accuracy(), ev.confusion.mean_iou(),
                   ev.clouds, ev.ms_per_cloud(), now_s() - t0);
      pooled.merge(ev);
    }
    result["validation"] = nlohmann::json::parse(pooled.json());
    result["validation"]["folds"] = K;
    result["validation"]["folds_run"] = last - first;
    result["validation"]["train_seconds"] = train_s;
    if (!o.common.json) std::printf("held-out (k-fold by cloud):\n%s", pooled.text().c_str());
    if (!o.val_fold.empty()) {
      result["out"] = o.out;
      if (o.common.json) print_json(result);
      return;
    }
  }
  if (!o.out.empty()) {
    const double t0 = now_s();
    train_one(model, cfgs, clouds, {}, o.out, "[all] ");
    result["out"] = o.out;
    result["train_seconds"] = now_s() - t0;
    if (!o.common.json)
      std::printf("trained on %zu clouds in %.1f s -> %s\n", clouds.size(), now_s() - t0, o.out.c_str());
  }
  if (o.common.json) print_json(result);
}
}  // namespace

void add_train_grape(CLI::App& train) {
  auto o = std::make_shared<TrainGrapeOptions>();
  auto* cmd = train.add_subcommand("grape", "Train a grape bunch segmentation model (GBDT, PointResNet, PointNet++)");
  cmd->add_option("--data", o->data, "Folder of labelled text clouds (directly or under points/)")->required();
  cmd->add_option("--model", o->model,
                  "gbdt | pointresnet | pointnet2 (default: the --config preset's arch, else gbdt)");
  cmd->add_option("--features", o->features, "Network inputs: xyz | xyzn | xyzrgb | xyzrgbn");
  cmd->add_option("--out", o->out, "Model file to write (.json for gbdt, .pt for networks)");
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
