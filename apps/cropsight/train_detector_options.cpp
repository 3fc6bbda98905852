// The options of `cropsight train detector` (train_detector_options.hpp).
#include "train_detector_options.hpp"

#include <tuple>

#include "cropsight/core/error.hpp"

namespace cropsight::cli {

std::string train_detector_checkpoint(const TrainDetectorOptions& o) {
  if (o.out.empty()) throw Error("--out", "give the model file to write");
  const io::OutputPolicy policy =
      output_policy("train detector", o.force, {o.data.coco, o.data.voc, o.data.images, o.common.config});
  io::check_output_file(o.out, policy);
  const std::string checkpoint = o.checkpoint.empty() ? o.out + ".ckpt" : o.checkpoint;
  if (o.resume)
    io::check_not_an_input(checkpoint, policy);
  else
    io::check_output_file(checkpoint, policy);
  return checkpoint;
}

nn::DetectorTrainingConfig train_detector_preset(const TrainDetectorOptions& o) {
  return nn::detector_training_config(o.common.config_map(), o.common.config.empty() ? "--set" : o.common.config);
}

void apply_train_detector_options(const TrainDetectorOptions& o, const std::vector<std::string>& classes,
                                  nn::CenterNetConfig& cfg) {
  std::string names;
  for (const auto& c : classes) names += (names.empty() ? "" : ",") + c;
  cfg.class_names = names;
  if (!o.input.empty()) std::tie(cfg.input_width, cfg.input_height) = parse_input_size(o.input);
  if (o.epochs) cfg.epochs = o.epochs;
  if (o.width) cfg.width = o.width;
  if (o.batch) cfg.batch_size = o.batch;
  if (o.lr > 0) cfg.lr = o.lr;
  cfg.threads = o.threads;
  cfg.seed = o.seed;
  cfg.validate("train detector");
}

}  // namespace cropsight::cli
