// cropsight train detector: trains the project's CenterNet from scratch on a COCO or
// VOC set, with augmentation, a held-out split scored every epoch, checkpoints and resume.
//
//   cropsight train detector (--coco ANN.json | --voc DIR) --images DIR [--classes a,b] --out det.pt
//       [--epochs N] [--input WxH] [--width W] [--batch N] [--lr X] [--val-split F] [--split-seed S]
//       [--seed S] [--threads N] [--checkpoint PATH] [--resume] [--no-augment]
//       [--config PRESET] [--set detector.KEY=V | augment.KEY=V] [--json]
//
// One progress line per epoch on stderr (losses, held-out AP50, seconds); stdout holds the result.
#include <cstdio>
#include <nlohmann/json.hpp>
#include <tuple>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/nn/center_net.hpp"
#include "cropsight/nn/detection_augment.hpp"
#include "detector_cli.hpp"

namespace cropsight::cli {
namespace train_detector_cmd {

struct TrainDetectorOptions {
  DatasetOptions data;
  std::string out, input, checkpoint;
  int epochs = 0, width = 0, batch = 0, threads = 1;
  double lr = 0, val_split = 0.2;
  std::uint64_t seed = 1, split_seed = 1;
  bool resume = false, no_augment = false, force = false, quiet = false;
  CommonOptions common;
};

// The outputs, checked before minutes of training; returns the checkpoint's path. The checkpoint is
// an output too: started afresh (an existing one replaced) only with --force, resumed with --resume.
std::string checked_outputs(const TrainDetectorOptions& o) {
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

// Long on purpose: options to configs, the split, the training with its per-epoch log and the summary.
void run(const TrainDetectorOptions& o) {
  const std::string checkpoint = checked_outputs(o);
  const ConfigMap map = o.common.config_map();
  const std::string where = o.common.config.empty() ? "--set" : o.common.config;
  // Every key belongs to one of the two sections: a key without its section (`mask_weight` for
  // `detector.mask_weight`) would otherwise be ignored without a word.
  for (const auto& [key, value] : map)
    if (key.rfind("detector.", 0) != 0 && key.rfind("augment.", 0) != 0)
      throw Error(where, "unknown key '" + key + "' (keys are detector.* or augment.*)");
  const nn::DetectionDataset set = load_dataset(o.data);
  nn::CenterNetConfig cfg;
  nn::DetectionAugmentConfig aug;
  apply_config(cfg, map, where, "detector.");
  apply_config(aug, map, where, "augment.");
  std::string names;
  for (const auto& c : set.classes) names += (names.empty() ? "" : ",") + c;
  cfg.class_names = names;
  if (!o.input.empty()) std::tie(cfg.input_width, cfg.input_height) = parse_input_size(o.input);
  if (o.epochs) cfg.epochs = o.epochs;
  if (o.width) cfg.width = o.width;
  if (o.batch) cfg.batch_size = o.batch;
  if (o.lr > 0) cfg.lr = o.lr;
  cfg.threads = o.threads;
  cfg.seed = o.seed;
  cfg.validate("train detector");

  const Split split = split_indices(set.samples.size(), o.val_split, o.split_seed);
  std::vector<nn::DetectionSample> train, val;
  nlohmann::json val_names = nlohmann::json::array();
  for (auto i : split.train) train.push_back(set.samples[i]);
  for (auto i : split.val) val.push_back(set.samples[i]), val_names.push_back(set.samples[i].name);

  if (!o.resume) {  // the inputs are read: an earlier checkpoint goes (--force said so, checked_outputs)
    std::error_code ec;
    std::filesystem::remove(checkpoint, ec);
  }
  nn::CenterNet net(cfg);
  if (!o.quiet)
    std::fprintf(stderr, "train detector: %zu train / %zu held-out images, %zu classes, %zu parameters, input %dx%d\n",
                 train.size(), val.size(), set.classes.size(), net.parameter_count(), cfg.input_width,
                 cfg.input_height);
  const Stopwatch clock;
  std::function<nn::DetectionSample(const nn::DetectionSample&, std::uint64_t)> augment;
  if (!o.no_augment)
    augment = [&](const nn::DetectionSample& s, std::uint64_t draw) {
      return nn::augment_detection(s, train, aug, draw);
    };
  nlohmann::json epochs = nlohmann::json::array();
  const auto logs = net.train(
      train, val, augment,
      [&](const nn::DetectorEpochLog& l) {
        if (!o.quiet)
          std::fprintf(
              stderr,
              "epoch %d/%d  loss %.4f (heatmap %.4f size %.4f offset %.4f mask %.4f)  held-out AP50 %s  %.1f s\n",
              l.epoch, cfg.epochs, l.loss, l.heatmap_loss, l.size_loss, l.offset_loss, l.mask_loss,
              l.val_ap50 < 0 ? "-" : std::to_string(l.val_ap50).substr(0, 5).c_str(), l.seconds);
        epochs.push_back({{"epoch", l.epoch},
                          {"loss", json_number(l.loss)},
                          {"val_ap50", l.val_ap50 < 0 ? nlohmann::json() : json_number(l.val_ap50)},
                          {"seconds", json_number(l.seconds)}});
      },
      checkpoint);
  // Mask thresholds per class from the training images (never the held-out ones).
  const std::vector<float> mask_thresholds = calibrate_masks(net, train);
  if (!mask_thresholds.empty()) {
    std::string list;
    for (float t : mask_thresholds) list += (list.empty() ? "" : " ") + std::to_string(t).substr(0, 4);
    if (!o.quiet)
      std::fprintf(stderr, "mask thresholds per class (best IoU on the training images): %s\n", list.c_str());
  }
  net.save(o.out);
  const double seconds = clock.seconds();
  nlohmann::json result = {{"out", o.out},
                           {"classes", set.classes},
                           {"train_images", train.size()},
                           {"val_images", val_names},
                           {"epochs", cfg.epochs},
                           {"threads", cfg.threads},
                           {"parameters", net.parameter_count()},
                           {"train_seconds", json_number(seconds)},
                           {"mask_thresholds", rounded_thresholds(net.config().mask_threshold_values())},
                           {"log", epochs}};
  if (!logs.empty() && logs.back().val_ap50 >= 0) result["val_ap50"] = json_number(logs.back().val_ap50);
  if (o.common.json)
    print_json(result);
  else
    std::printf("trained on %zu images in %.1f s -> %s\n", train.size(), seconds, o.out.c_str());
}
}  // namespace train_detector_cmd

void add_train_detector(CLI::App& train) {
  using namespace train_detector_cmd;
  auto o = std::make_shared<TrainDetectorOptions>();
  auto* cmd = train.add_subcommand("detector", "Train the CenterNet 2D detector (boxes and masks) from scratch");
  add_dataset_options(cmd, o->data);
  cmd->add_option("--out", o->out, "Model file to write (.pt)")->required();
  add_force_flag(cmd, o->force);
  cmd->add_flag("--quiet", o->quiet, "No progress lines");
  cmd->add_option("--epochs", o->epochs, "Training epochs (default 60)");
  cmd->add_option("--input-size", o->input, "Network input WxH, multiples of 32 (default 256x256)");
  add_deprecated_option(cmd, "--input", o->input, "--input-size");
  cmd->add_option("--width", o->width, "Base channel width (default 16)");
  cmd->add_option("--batch", o->batch, "Images per step (default 4)");
  cmd->add_option("--lr", o->lr, "Adam learning rate (default 1e-3)");
  cmd->add_option("--val-split", o->val_split, "Fraction of the images held out and scored every epoch (0..1)");
  cmd->add_option("--split-seed", o->split_seed, "Seed of the held-out split");
  cmd->add_option("--seed", o->seed, "Seed of the weights, the shuffling and the augmentation");
  cmd->add_option("--threads", o->threads, "libtorch threads")->check(CLI::Range(1, 256));
  cmd->add_option("--checkpoint", o->checkpoint, "Checkpoint written every epoch (default OUT.ckpt)");
  cmd->add_flag("--resume", o->resume, "Continue from the checkpoint (else it is started afresh)");
  cmd->add_flag("--no-augment", o->no_augment, "Train on the images as they are");
  add_json_flag(cmd, o->common);
  add_config_options(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
