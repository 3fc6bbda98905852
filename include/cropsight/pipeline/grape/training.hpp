#pragma once
// Training grape segmentation models of either kind (GBDT or network) and k-fold
// cross-validation by cloud: what `cropsight train grape` runs, for library users too.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "cropsight/core/cloud.hpp"
#include "cropsight/nn/point_segmenter.hpp"
#include "cropsight/pipeline/grape/eval.hpp"
#include "cropsight/pipeline/grape/gbdt.hpp"

namespace cropsight::pipeline::grape {

/// The model to train and its configuration (only the one of `model`'s kind is used).
struct TrainConfig {
  std::string model = "gbdt";  ///< "gbdt" | "pointresnet" | "pointnet2" (net.arch names the network)
  GbdtConfig gbdt;
  nn::PointNetConfig net;
};

/// Progress lines (no trailing newline); may be empty.
using TrainLog = std::function<void(const std::string&)>;

/// Trains one model on the labelled `train` clouds and writes it to `out` (XGBoost JSON for the
/// GBDT, a .pt archive for a network). A network validates on `val` every net.val_every epochs
/// (val may be empty). `log` receives the GBDT's progress, or a network's summary line and one
/// line per epoch ("epoch 3/40  loss 0.5123  train acc 0.8012  [val mIoU 0.6012  ]lr 1.00e-03
/// 12.3 s"). Throws Error for bad clouds or configurations and a model that cannot be written.
void train_grape_model(const TrainConfig& cfg, const std::vector<Cloud>& train, const std::vector<Cloud>& val,
                       const std::filesystem::path& out, const TrainLog& log = {});

/// Which folds a cross-validation runs.
struct FoldPlan {
  int folds = 4;                 ///< K: clouds dealt into K folds (grape_folds), K <= clouds
  int first = 0, last = 4;       ///< folds run: first..last-1, each held out once (0-based)
  std::uint64_t split_seed = 1;  ///< seed of grape_folds
  int eval_threads = 2;          ///< threads of the held-out evaluation
  /// Where a fold's model is written: empty = a temporary file, removed once the fold is
  /// evaluated (however it ends); else this file, kept (meaningful for a single fold).
  std::filesystem::path keep_model;
};

struct CrossValidation {
  Figures pooled;            ///< held-out evaluations of the folds run, merged
  double train_seconds = 0;  ///< training wall time summed over the folds run (evaluation excluded)
};

/// For each fold k of `plan`: trains on the other folds' clouds (a network validating on fold k),
/// evaluates the trained model on fold k and merges the figures. `log` receives the training
/// progress and one held-out line per fold, each prefixed with "[fold k/K] " (k 1-based).
CrossValidation cross_validate_grape(const TrainConfig& cfg, const std::vector<Cloud>& clouds, const FoldPlan& plan,
                                     const TrainLog& log = {});

}  // namespace cropsight::pipeline::grape
