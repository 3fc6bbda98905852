// cropsight eval detector: scores the project's 2D detector (.pt or .onnx) on a labelled set
//: per class COCO box AP50 and AP50:95 and the mask head's pixel accuracy and IoU
// (nn/detector_eval.hpp says how).
//
//   cropsight eval detector (--coco ANN.json | --voc DIR) --images DIR --model M(.pt|.onnx)
//       [--classes a,b] [--val-split F --split-seed S] [--mask-threshold T] [--masks-in-boxes]
//       [--threads N] [--json]
//
// Masks are thresholded at the model's per-class mask_thresholds (set by train detector /
// tune-mask-thresholds on training images; 0.5 for older models) unless --mask-threshold gives one
// value for every class.
//
// With --val-split only the held-out images of that split are scored: the same images `train
// detector` held out with the same fraction and seed (nn::split_detection_set).
// --classes defaults to the model's class names, so class ids match the model's.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/config_yaml.hpp"
#include "cropsight/nn/center_onnx.hpp"
#include "cropsight/nn/detector_eval.hpp"
#include "detector_cli.hpp"

namespace cropsight::cli {
namespace eval_detector_cmd {

struct EvalDetectorOptions {
  DatasetOptions data;
  std::string model;
  double val_split = 0, mask_threshold = -1;  // < 0: the model's per-class thresholds
  std::uint64_t split_seed = 1;
  int threads = 1;
  bool masks_in_boxes = false;
  CommonOptions common;
};

void run(EvalDetectorOptions o) {
  auto det = nn::load_center_detector(io::find_model(o.model).string(), o.threads);
  if (o.data.classes.empty())
    for (const auto& c : det->class_names()) o.data.classes += (o.data.classes.empty() ? "" : ",") + c;
  nn::DetectionDataset set = load_dataset(o.data);
  std::vector<nn::DetectionSample> scored;
  nlohmann::json names = nlohmann::json::array();
  if (o.val_split > 0) {
    scored = nn::split_detection_set(std::move(set.samples), o.val_split, o.split_seed).val;
  } else {
    scored = std::move(set.samples);
  }
  for (const auto& s : scored) names.push_back(s.name);
  double ms = 0;
  const nn::DetectorScore score = nn::evaluate_detector(*det, scored, float(o.mask_threshold), &ms, o.masks_in_boxes);
  const nn::CenterNetConfig& cfg = nn::center_net_config(*det, o.model);
  std::vector<float> thresholds = cfg.mask_threshold_values(o.model);
  const std::string input = input_size_text(cfg);
  if (o.mask_threshold >= 0) std::fill(thresholds.begin(), thresholds.end(), float(o.mask_threshold));
  if (o.common.json) {
    nlohmann::json classes = nlohmann::json::array();
    for (const auto& c : score.classes)
      classes.push_back({{"class", c.name},
                         {"truths", c.truths},
                         {"detections", c.detections},
                         {"box_ap50", json_number(c.ap50)},
                         {"box_ap50_95", json_number(c.ap50_95)},
                         {"pixel_accuracy", json_number(c.pixel_accuracy)},
                         {"iou", json_number(c.iou)},
                         {"truth_pixels", c.truth_pixels},
                         {"predicted_pixels", c.predicted_pixels}});
    print_json({{"model", o.model},
                {"images", score.images},
                {"masked_images", score.masked_images},
                {"image_names", names},
                {"ap", "COCO bbox: greedy best-unmatched matching, 101-point interpolation"},
                {"mask_thresholds", rounded_thresholds(thresholds)},
                {"mask_upsampling", cfg.mask_upsampling},
                {"flip_test", cfg.flip_test},
                {"mask_inputs", cfg.mask_inputs},
                {"mask_inputs_flip_test", cfg.mask_passes_flip()},
                {"masks_in_boxes", o.masks_in_boxes},
                {"input", input},
                {"ms_per_image", json_number(ms)},
                {"classes", classes}});
  } else {
    std::printf("%d images (%d with masks), input %s, masks %s\n", score.images, score.masked_images, input.c_str(),
                cfg.mask_upsampling.c_str());
    for (std::size_t i = 0; i < score.classes.size(); ++i) {
      const auto& c = score.classes[i];
      std::printf("%-12s box AP50 %.3f  AP50:95 %.3f  pixel acc %.3f  IoU %.3f  (mask threshold %.2f)\n",
                  c.name.c_str(), c.ap50, c.ap50_95, c.pixel_accuracy, c.iou,
                  i < thresholds.size() ? thresholds[i] : 0.5f);
    }
  }
}
}  // namespace eval_detector_cmd

void add_eval_detector(CLI::App& eval) {
  using namespace eval_detector_cmd;
  auto o = std::make_shared<EvalDetectorOptions>();
  auto* cmd =
      eval.add_subcommand("detector", "Score the 2D detector: COCO box AP per class, mask pixel accuracy / IoU");
  add_dataset_options(cmd, o->data);
  cmd->add_option("--model", o->model, "Detector: .pt (libtorch) or .onnx (OpenCV DNN)")->required();
  cmd->add_option("--val-split", o->val_split, "Score only the held-out images of this split (as train detector)");
  cmd->add_option("--split-seed", o->split_seed, "Seed of the held-out split");
  cmd->add_option("--mask-threshold", o->mask_threshold,
                  "Mask head score a pixel needs, for every class (default: the model's per-class mask_thresholds)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_flag("--masks-in-boxes", o->masks_in_boxes,
                "Each class's mask only inside its detected boxes (nn::masks_in_boxes), not over the whole image");
  cmd->add_option("--threads", o->threads, "libtorch threads (.pt)")->check(CLI::Range(1, 256));
  add_json_flag(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
