#pragma once
// The options of `cropsight train detector` and what they mean: the outputs they name and the
// training configuration (preset, --set, the set's classes and the flags that override them).
#include <cstdint>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "cropsight/nn/detection_augment.hpp"
#include "detector_cli.hpp"

namespace cropsight::cli {

struct TrainDetectorOptions {
  DatasetOptions data;
  std::string out, input, checkpoint;
  int epochs = 0, width = 0, batch = 0, threads = 1;
  double lr = 0, val_split = 0.2;
  std::uint64_t seed = 1, split_seed = 1;
  bool resume = false, no_augment = false, force = false, quiet = false;
  CommonOptions common;
};

/// The outputs, checked before minutes of training; returns the checkpoint's path. The checkpoint
/// is an output too: started afresh (an existing one replaced) only with --force, resumed with
/// --resume. Throws Error naming the option or the file.
std::string train_detector_checkpoint(const TrainDetectorOptions& o);

/// The preset's and --set's detector.* and augment.* keys, read before the images so that a typo
/// costs nothing. Throws Error naming the preset or "--set".
nn::DetectorTrainingConfig train_detector_preset(const TrainDetectorOptions& o);

/// `cfg` with the set's classes and the flags that override the preset, validated.
void apply_train_detector_options(const TrainDetectorOptions& o, const std::vector<std::string>& classes,
                                  nn::CenterNetConfig& cfg);

}  // namespace cropsight::cli
