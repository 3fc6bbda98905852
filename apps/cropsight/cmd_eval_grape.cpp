// cropsight eval grape: OAcc / mAcc / mIoU, per-class accuracy and IoU and time per cloud of a
// trained grape segmentation model on labelled text clouds.
//
//   cropsight eval grape --clouds DIR (--model MODEL | --config PRESET) [--fold k/K] [--limit N]
//   [--sampled [--sampling random|fps] [--carry-k K]] [--votes N] [--ensemble MODEL2 [--ensemble-weight W]] [--json]
//
// --fold k/K evaluates only the clouds of fold k (the split of `train grape --val-fold k/K`),
// so that a model is only ever scored on clouds it was not trained on (configs/grape-best-fold1.yaml
// is the shipped best recipe with its models trained without fold 1 of 4).
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/core/threads.hpp"
#include "cropsight/pipeline/grape/cloud_files.hpp"
#include "cropsight/pipeline/grape/eval.hpp"
#include "cropsight/pipeline/grape/model.hpp"
#include "cropsight/pipeline/grape/segmenter.hpp"
#include "cropsight/pipeline/grape/truth.hpp"
#include "grape_cli.hpp"
#include "grape_segmenter_options.hpp"

namespace cropsight::cli {
namespace eval_grape_cmd {
struct EvalGrapeOptions {
  CommonOptions common;
  std::string data, fold;
  int limit = 0, threads = 2;
  bool limit_set = false;  // --limit given (0 or less is an error, not "all")
  GrapeSegmenterOptions segmenter;
  std::uint64_t split_seed = 1;
};

void run(const EvalGrapeOptions& o) {
  if (o.data.empty()) throw Error("--clouds", "give the labelled clouds (a folder, files or a list)");
  check_thread_count(o.threads, "--threads");
  auto cfg = o.segmenter.config();
  cfg.threads = o.threads;
  const pipeline::grape::Segmenter segmenter(cfg, "command line");
  const pipeline::grape::Model& model = segmenter.model();
  if (o.limit_set && o.limit < 1) throw Error("--limit", "must be at least 1, got " + std::to_string(o.limit));
  auto files = pipeline::grape::list_cloud_files(o.data);
  if (o.limit_set && std::size_t(o.limit) < files.size()) files.resize(std::size_t(o.limit));
  if (!o.fold.empty()) {
    const auto [k, K] = pipeline::grape::parse_fold(o.fold, "--fold");
    // Folds are dealt round-robin: K <= clouds leaves none empty (an empty fold scored "nan").
    if (std::size_t(K) > files.size())
      throw Error("--fold", std::to_string(K) + " folds need at least " + std::to_string(K) + " clouds, " + o.data +
                                " has " + std::to_string(files.size()) + (o.limit_set ? " (after --limit)" : ""));
    const auto fold = pipeline::grape::grape_folds(files.size(), K, o.split_seed);
    std::vector<std::filesystem::path> keep;
    for (std::size_t i = 0; i < files.size(); ++i)
      if (fold[i] == k) keep.push_back(files[i]);
    files = keep;
  }
  const auto clouds = pipeline::grape::load_grape_clouds(files);
  const auto ev = pipeline::grape::evaluate_grape(model, clouds);
  if (o.common.json) {
    auto j = grape_evaluation_json(ev);
    j["model"] = model.kind();
    if (model.kind() != "gbdt") j["mode"] = segmenter.mode();
    GrapeSegmenterOptions::describe(cfg, j);
    print_json(j);
  } else {
    std::printf("model %s (%s)\n%s", cfg.model.c_str(), model.kind().c_str(), ev.text().c_str());
  }
}
}  // namespace eval_grape_cmd

void add_eval_grape(CLI::App& eval) {
  using namespace eval_grape_cmd;
  auto o = std::make_shared<EvalGrapeOptions>();
  auto* cmd = eval.add_subcommand("grape", "Evaluate a grape segmentation model on labelled text clouds");
  cmd->add_option("--clouds", o->data,
                  "Labelled clouds: a folder (directly or under points/), files or a comma-separated list; the "
                  "dataset's .txt, or .ply / .pcd with a label field");
  add_deprecated_option(cmd, "--data", o->data, "--clouds");
  cmd->add_option("--fold", o->fold, "k/K: evaluate only fold k of the by-cloud split");
  cmd->add_option("--split-seed", o->split_seed, "Seed of the fold split (as in train grape)");
  auto* limit = cmd->add_option("--limit", o->limit, "Use only the first N clouds, N >= 1");
  cmd->add_option("--threads", o->threads, "Threads, 1.." + std::to_string(kMaxThreads) + " (default 2)");
  o->segmenter.add_options(cmd);  // no default preset: the shipped models saw every shared cloud
  add_json_flag(cmd, o->common);
  cmd->callback([o, limit] {
    o->limit_set = limit->count() > 0;
    run(*o);
  });
}

}  // namespace cropsight::cli
