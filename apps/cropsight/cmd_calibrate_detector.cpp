// cropsight tune-mask-thresholds (formerly calibrate-detector) --model IN.pt (--coco ANN.json | --voc DIR) --images DIR
//     [--classes a,b] [--val-split F --split-seed S] [--input WxH] [--mask-upsampling M] [--flip-test[=false]]
//     [--mask-inputs WxH[,WxH...]|none]
//     --out OUT.pt [--json]
//
// Sets a trained detector's per-class mask thresholds (CenterNetConfig::mask_thresholds) to
// each class's best-IoU value on the images `train detector` trained on: with --val-split and
// --split-seed, the images that split does not hold out, so that `eval detector` with the same
// split still scores images nothing was chosen on. `train detector` does the same at its end;
// this verb brings models trained before that (the shipped ones) up to date. --input sets the
// inference resolution first (the network is fully convolutional: the same weights at a larger
// input give the stride-4 mask head finer cells), --mask-upsampling how the mask head is brought
// back to pixels (default bilinear), --flip-test[=false] turns the flip test on or off (heads averaged
// with the mirrored image's; otherwise the model's setting stays), --mask-inputs the multi-scale mask test
// (further inputs whose mask heads are averaged with the main one's; "none" clears it); the thresholds are then
// calibrated for them. The weights are unchanged; export-detector carries the settings into the ONNX file.
#include <cstdio>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/config_yaml.hpp"
#include "cropsight/nn/center_net.hpp"
#include "cropsight/nn/detector_eval.hpp"
#include "detector_cli.hpp"

namespace cropsight::cli {

void add_calibrate_detector(CLI::App& app) {
  struct Options {
    DatasetOptions data;
    std::string model, out, input, upsampling = "bilinear", mask_inputs;
    double val_split = 0;
    std::uint64_t split_seed = 1;
    bool flip_test = false, mask_flip = true, force = false;
    const CLI::Option* flip_given = nullptr;
    CommonOptions common;
  };
  auto o = std::make_shared<Options>();
  // The old name stays an alias for one release (main.cpp prints the deprecation line).
  auto* cmd = app.add_subcommand("tune-mask-thresholds",
                                 "Set a detector's per-class mask thresholds from its training images (.pt)");
  cmd->alias("calibrate-detector");
  cmd->add_option("--model", o->model, "Detector model written by train detector (.pt)")->required();
  add_dataset_options(cmd, o->data);
  cmd->add_option("--val-split", o->val_split,
                  "Held-out fraction of train detector's split: those images are not used");
  cmd->add_option("--split-seed", o->split_seed, "Seed of that split");
  cmd->add_option("--input-size", o->input,
                  "Inference input WxH, multiples of 32 (default: the model's; a later training would use it too)");
  add_deprecated_option(cmd, "--input", o->input, "--input-size");
  cmd->add_option("--mask-upsampling", o->upsampling, "bilinear | nearest: mask head cells to pixels")
      ->capture_default_str();
  o->flip_given = cmd->add_flag("--flip-test", o->flip_test,
                                "Average the heads with the mirrored image's (twice the inference time); "
                                "--flip-test=false turns it off (default: the model's setting)");
  cmd->add_option("--mask-inputs", o->mask_inputs,
                  "Multi-scale mask test: further inputs WxH[,WxH...] whose mask heads are averaged with the main "
                  "input's (boxes stay the main input's); none = off (default: the model's setting)");
  cmd->add_flag("--mask-inputs-flip-test", o->mask_flip,
                "With --mask-inputs: the extra passes use the flip test too when it is on (default true; =false: "
                "one pass each)");
  cmd->add_option("--out", o->out, "Model file to write (.pt)")->required();
  add_force_flag(cmd, o->force);
  add_json_flag(cmd, o->common);
  cmd->callback([o] {
    io::check_output_file(
        o->out, output_policy("tune-mask-thresholds", o->force, {o->model, o->data.coco, o->data.voc, o->data.images}));
    if (o->val_split < 0 || o->val_split >= 1) throw Error("--val-split", "must be in [0, 1)");
    nn::CenterNet net = nn::CenterNet::load(io::find_model(o->model).string(), 1);
    if (!o->input.empty()) {
      const auto [w, h] = parse_input_size(o->input);
      net.set_input_size(w, h);
    }
    net.set_mask_upsampling(o->upsampling);
    if (o->flip_given->count() > 0) net.set_flip_test(o->flip_test);
    if (!o->mask_inputs.empty()) net.set_mask_inputs(o->mask_inputs == "none" ? "" : o->mask_inputs, o->mask_flip);
    if (o->data.classes.empty())
      for (const auto& c : net.class_names()) o->data.classes += (o->data.classes.empty() ? "" : ",") + c;
    nn::DetectionDataset set = load_dataset(o->data);
    const std::vector<nn::DetectionSample> train =
        nn::split_detection_set(std::move(set.samples), o->val_split, o->split_seed).train;
    const std::vector<float> t = nn::calibrate_center_net_masks(net, train);
    const std::string source = o->data.coco.empty() ? o->data.voc : o->data.coco;
    if (t.empty()) throw Error(source, "no training image has masks (COCO polygons): nothing to calibrate");
    net.save(o->out);
    if (o->common.json) {
      print_json({{"out", o->out},
                  {"classes", net.class_names()},
                  {"input", input_size_text(net.config())},
                  {"mask_upsampling", net.config().mask_upsampling},
                  {"flip_test", net.config().flip_test},
                  {"mask_inputs", net.config().mask_inputs},
                  {"mask_inputs_flip_test", net.config().mask_passes_flip()},
                  {"mask_thresholds", rounded_thresholds(t)},
                  {"images", train.size()}});
    } else {
      std::printf("mask thresholds from %zu training images:", train.size());
      const auto names = net.class_names();
      for (std::size_t c = 0; c < t.size(); ++c) std::printf(" %s %.2f", names[c].c_str(), t[c]);
      const std::string extra = net.config().mask_inputs.empty() ? "" : ", masks also at " + net.config().mask_inputs;
      std::printf(" (input %s, %s masks%s%s) -> %s\n", input_size_text(net.config()).c_str(),
                  net.config().mask_upsampling.c_str(), net.config().flip_test ? ", flip test" : "", extra.c_str(),
                  o->out.c_str());
    }
  });
}

}  // namespace cropsight::cli
