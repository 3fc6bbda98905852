#pragma once
// The options of `cropsight train grape` and what they mean: checks, the training configuration
// (preset, --set and the flags that override it) and the fold plan of a cross-validation.
#include <cstdint>
#include <string>

#include "cli_common.hpp"
#include "cropsight/pipeline/grape/training.hpp"

namespace cropsight::cli {

struct TrainGrapeOptions {
  CommonOptions common;
  std::string data, model, features = "xyzrgbn", out, val_fold, checkpoint;  // model "": from the preset
  int epochs = 0, folds = 0, limit = 0;  // meaningful only when given (the *_set flags)
  bool force = false, quiet = false;
  bool epochs_set = false, folds_set = false, limit_set = false, threads_set = false;
  int threads = 0;  // unset: the preset's value (2); an explicit --threads wins over --config/--set
  int eval_threads() const { return threads_set ? threads : 2; }
  std::uint64_t split_seed = 1;
};

/// Options first, each named: 0 or a negative count used to mean "the preset's" or "all"
/// without a word. Throws Error naming the option.
void check_train_grape_options(const TrainGrapeOptions& o);

/// The configuration to train with, built and validated before any cloud is loaded, so that a
/// bad --set value fails at once and names its key (not deep inside XGBoost or libtorch). A
/// preset names its network (`arch`); without --model that decides, else gbdt.
pipeline::grape::TrainConfig train_grape_config(const TrainGrapeOptions& o);

/// --val-fold k/K (that fold, its model kept at --out) or --folds K (all, temporary models) as a
/// plan for `clouds` clouds. Folds are dealt round-robin: K <= clouds leaves none empty (an
/// empty fold scored "nan"), so more folds than clouds throw Error.
pipeline::grape::FoldPlan train_grape_fold_plan(const TrainGrapeOptions& o, std::size_t clouds);

}  // namespace cropsight::cli
