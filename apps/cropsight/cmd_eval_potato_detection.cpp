// cropsight eval potato-detection: the paper's metric (Pascal VOC all-point AP with
// inclusive pixel areas) on a folder of images with VOC annotations, from the detector or from
// saved detection files (--detections: so the paper's own outputs can be scored).
#include <cstdio>

#include "commands.hpp"
#include "cropsight/pipeline/potato/detection_eval.hpp"
#include "potato_cli.hpp"

namespace cropsight::cli {
namespace eval_potato_detection_cmd {

struct Options {
  CommonOptions common;
  std::string images, annotations, detections;
};

void run(const Options& o) {
  const auto set = pipeline::potato::load_annotated_images(o.images, o.annotations);
  pipeline::potato::DetectionEvalResult r;
  if (!o.detections.empty()) {
    if (!o.common.sets.empty() || !o.common.config.empty())
      throw Error("--detections", "scores saved files; --config and --set do not apply");
    r = pipeline::potato::evaluate_saved_detections(set, o.detections);
  } else {
    auto detector = potato_detector(o.common);
    r = pipeline::potato::evaluate_detector(*detector, set);
  }
  const nlohmann::json j = {{"ap50", json_number(r.ap.ap50)},
                            {"ap75", json_number(r.ap.ap75)},
                            {"map50_95", json_number(r.ap.map50_95)},
                            {"images", r.ap.images},
                            {"boxes", r.ap.truths},
                            {"detections", r.ap.detections},
                            {"ms_per_image", r.ms_per_image},
                            {"source", o.detections.empty() ? "detector" : o.detections}};
  if (o.common.json) {
    print_json(j);
  } else {
    std::printf("AP50 %.4f  AP75 %.4f  mAP50:95 %.4f  (%lld images, %lld boxes, %lld detections, %.2f ms/image)\n",
                r.ap.ap50, r.ap.ap75, r.ap.map50_95, (long long)r.ap.images, (long long)r.ap.truths,
                (long long)r.ap.detections, r.ms_per_image);
  }
}

}  // namespace eval_potato_detection_cmd

void add_eval_potato_detection(CLI::App& eval) {
  using namespace eval_potato_detection_cmd;
  auto o = std::make_shared<Options>();
  auto* cmd = eval.add_subcommand("potato-detection", "Pascal VOC AP of potato detections (the paper's metric)");
  cmd->add_option("--images", o->images, "Folder of images")->required();
  cmd->add_option("--annotations", o->annotations, "Folder of Pascal VOC .xml annotations")->required();
  cmd->add_option("--detections", o->detections, "Score saved <stem>.txt files instead of running the detector");
  add_json_flag(cmd, o->common);
  add_config_options(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
