// cropsight train grape: trains the grape bunch segmentation models (issue 6) on the dataset's
// labelled text clouds, with optional k-fold cross-validation by cloud.
//
//   cropsight train grape --data DIR --model gbdt|pointresnet|pointnet2
//       [--features xyz|xyzn|xyzrgb|xyzrgbn] --out MODEL [--epochs N]
//       [--val-fold k/K | --folds K] [--limit N] [--config PRESET] [--set key=value] [--json]
//
// --val-fold k/K trains on every fold but k and reports the metrics of fold k; --folds K runs
// all K folds and reports the pooled metrics, then (with --out) trains on every cloud.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/grape_text.hpp"
#include "cropsight/nn/point_segmenter.hpp"
#include "cropsight/pipeline/grape_eval.hpp"
#include "cropsight/pipeline/grape_gbdt.hpp"
#include "cropsight/pipeline/grape_model.hpp"

namespace cropsight::cli {
namespace {
namespace fs = std::filesystem;

struct TrainGrapeOptions {
  CommonOptions common;
  std::string data, model = "gbdt", features = "xyzrgbn", out, val_fold, checkpoint;
  int epochs = -1, folds = 0, limit = 0;
  int threads = 0;  // 0 = the preset's value (2); an explicit --threads wins over --config/--set
  int eval_threads() const { return threads > 0 ? threads : 2; }
  std::uint64_t split_seed = 1;
};

double now_s() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

// Trains one model on `train` (validating networks on `val`) and writes it to `out`.
void train_one(const TrainGrapeOptions& o, const ConfigMap& cfg_map, const std::vector<Cloud>& train,
               const std::vector<Cloud>& val, const fs::path& out, const std::string& tag) {
  if (o.model == "gbdt") {
    pipeline::GrapeGbdtConfig cfg;
    cfg.gbdt.nthread = cfg.features.threads = o.eval_threads();
    apply_config(cfg, cfg_map, "--config/--set");
    if (o.threads > 0) cfg.gbdt.nthread = cfg.features.threads = o.threads;
    auto model = pipeline::train_grape_gbdt(
        train, cfg, [&](const std::string& line) { std::fprintf(stderr, "%s%s\n", tag.c_str(), line.c_str()); });
    model.save(out);
    return;
  }
  nn::PointNetConfig cfg;
  cfg.arch = o.model;
  cfg.threads = o.eval_threads();
  apply_config(cfg, cfg_map, "--config/--set");
  if (o.threads > 0) cfg.threads = o.threads;  // the presets say threads: 2; --threads must still win
  cfg.arch = o.model;
  cfg.features = o.features;
  if (o.epochs > 0) cfg.epochs = o.epochs;
  cfg.checkpoint = o.checkpoint;
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
  if (o.model != "gbdt" && o.model != "pointresnet" && o.model != "pointnet2")
    throw Error("--model", "expected gbdt, pointresnet or pointnet2, got '" + o.model + "'");
  nn::feature_channels(o.features);
  if (o.threads < 0) throw Error("--threads", "must be at least 1");
  if (o.out.empty() && o.folds == 0) throw Error("--out", "required unless --folds is given");
  if (!o.val_fold.empty() && o.folds) throw Error("--folds", "use either --folds or --val-fold");
  const ConfigMap cfg_map = o.common.config_map(o.common.config.empty() ? "grape-" + o.model : "");

  auto files = io::list_grape_clouds(o.data);
  if (o.limit > 0 && std::size_t(o.limit) < files.size()) files.resize(std::size_t(o.limit));
  const auto clouds = pipeline::load_grape_clouds(files);
  nlohmann::json result = {{"model", o.model}, {"clouds", clouds.size()}};
  if (o.model != "gbdt") result["features"] = o.features;

  auto split = [&](int k, int K, std::vector<Cloud>& tr, std::vector<Cloud>& va) {
    const auto fold = pipeline::grape_folds(clouds.size(), K, o.split_seed);
    for (std::size_t i = 0; i < clouds.size(); ++i) (fold[i] == k ? va : tr).push_back(clouds[i]);
  };

  if (!o.val_fold.empty() || o.folds) {
    int K = o.folds, first = 0, last = o.folds;
    if (!o.val_fold.empty()) {
      auto [k, KK] = pipeline::parse_fold(o.val_fold, "--val-fold");
      K = KK, first = k, last = k + 1;
    }
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
                                             std::to_string(k) + (o.model == "gbdt" ? ".json" : ".pt"));
      const double t0 = now_s();
      train_one(o, cfg_map, tr, va, model_path, tag);
      train_s += now_s() - t0;
      const auto model = pipeline::GrapeModel::load(model_path, o.eval_threads());
      const auto ev = pipeline::evaluate_grape(model, va);
      if (o.val_fold.empty()) fs::remove(model_path);
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
    train_one(o, cfg_map, clouds, {}, o.out, "[all] ");
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
  cmd->add_option("--model", o->model, "gbdt | pointresnet | pointnet2");
  cmd->add_option("--features", o->features, "Network inputs: xyz | xyzn | xyzrgb | xyzrgbn");
  cmd->add_option("--out", o->out, "Model file to write (.json for gbdt, .pt for networks)");
  cmd->add_option("--epochs", o->epochs, "Network training epochs (overrides the preset)");
  cmd->add_option("--val-fold", o->val_fold, "k/K: train without fold k and report its metrics");
  cmd->add_option("--folds", o->folds, "Run K-fold cross-validation by cloud, then train on all (with --out)");
  cmd->add_option("--limit", o->limit, "Use only the first N clouds (quick runs)");
  cmd->add_option("--threads", o->threads,
                  "Threads for XGBoost / libtorch / FPFH (default: the preset's, 2); overrides --config/--set");
  cmd->add_option("--checkpoint", o->checkpoint, "Network checkpoint written every epoch and resumed from");
  cmd->add_option("--split-seed", o->split_seed, "Seed of the fold split");
  add_json_flag(cmd, o->common);
  add_config_options(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
