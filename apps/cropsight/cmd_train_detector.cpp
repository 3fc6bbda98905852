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
#include "cropsight/nn/detector_eval.hpp"
#include "detector_cli.hpp"
#include "train_detector_options.hpp"

namespace cropsight::cli {
namespace train_detector_cmd {

// One progress line on stderr (unless --quiet) and one JSON log entry per epoch.
nlohmann::json log_epoch(const TrainDetectorOptions& o, const nn::DetectorEpochLog& l, int epochs) {
  if (!o.quiet)
    std::fprintf(stderr,
                 "epoch %d/%d  loss %.4f (heatmap %.4f size %.4f offset %.4f mask %.4f)  held-out AP50 %s  %.1f s\n",
                 l.epoch, epochs, l.loss, l.heatmap_loss, l.size_loss, l.offset_loss, l.mask_loss,
                 l.val_ap50 < 0 ? "-" : std::to_string(l.val_ap50).substr(0, 5).c_str(), l.seconds);
  return {{"epoch", l.epoch},
          {"loss", json_number(l.loss)},
          {"val_ap50", l.val_ap50 < 0 ? nlohmann::json() : json_number(l.val_ap50)},
          {"seconds", json_number(l.seconds)}};
}

void run(const TrainDetectorOptions& o) {
  const std::string checkpoint = train_detector_checkpoint(o);
  nn::DetectorTrainingConfig t = train_detector_preset(o);
  nn::DetectionDataset set = load_dataset(o.data);
  apply_train_detector_options(o, set.classes, t.detector);
  const nn::CenterNetConfig& cfg = t.detector;
  const nn::DetectionSplit split = nn::split_detection_set(std::move(set.samples), o.val_split, o.split_seed);
  const std::vector<nn::DetectionSample>& train = split.train;
  nlohmann::json val_names = nlohmann::json::array();
  for (const auto& s : split.val) val_names.push_back(s.name);

  if (!o.resume) {  // the inputs are read: an earlier checkpoint goes (--force said so, checked_outputs)
    std::error_code ec;
    std::filesystem::remove(checkpoint, ec);
  }
  nn::CenterNet net(cfg);
  if (!o.quiet)
    std::fprintf(stderr, "train detector: %zu train / %zu held-out images, %zu classes, %zu parameters, input %dx%d\n",
                 train.size(), split.val.size(), set.classes.size(), net.parameter_count(), cfg.input_width,
                 cfg.input_height);
  const Stopwatch clock;
  std::function<nn::DetectionSample(const nn::DetectionSample&, std::uint64_t)> augment;
  if (!o.no_augment)
    augment = [&](const nn::DetectionSample& s, std::uint64_t draw) {
      return nn::augment_detection(s, train, t.augment, draw);
    };
  nlohmann::json epochs = nlohmann::json::array();
  const auto logs = net.train(
      train, split.val, augment, [&](const nn::DetectorEpochLog& l) { epochs.push_back(log_epoch(o, l, cfg.epochs)); },
      checkpoint);
  // Mask thresholds per class from the training images (never the held-out ones).
  const std::vector<float> mask_thresholds = nn::calibrate_center_net_masks(net, train);
  if (!mask_thresholds.empty() && !o.quiet) {
    std::string list;
    for (float v : mask_thresholds) list += (list.empty() ? "" : " ") + std::to_string(v).substr(0, 4);
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
