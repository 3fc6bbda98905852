// cropsight eval potato-orientation (paper Table 4.3): the orientation error (modulo
// 180°) of one segmentation + axis + input combination on the paper's folder layout. The
// evaluation is pipeline::potato::evaluate_orientation(); this file parses and formats.
// The boxes come from BoardBlobDetector (one colour blob on the white board; --boxes board, the
// default: the better measured on the shared shots) or from the potato preset's detector (--boxes
// detector, the paper's protocol).
#include <cstdio>
#include <memory>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/pipeline/potato/make_pipeline.hpp"
#include "cropsight/pipeline/potato/orientation_dataset.hpp"
#include "cropsight/pipeline/potato/pipeline.hpp"

namespace cropsight::cli {

namespace eval_potato_orientation_cmd {

struct Options {
  CommonOptions common;
  std::string rgb, depth, segmentation = "ours", axis = "pca", input = "depth";
  bool shots = false;  ///< also list every shot's estimate and error
  std::string boxes = "board", detector_config = "potato";
};

nlohmann::json to_json(const eval::OrientationStats& s) {
  return {{"count", s.count},
          {"failures", s.failures},
          {"mae_deg", json_number(s.mae_deg)},
          {"std_deg", json_number(s.std_deg)},
          {"max_deg", json_number(s.max_deg)}};
}

nlohmann::json groups(const std::vector<eval::OrientationStats>& g) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& s : g) j[s.key] = to_json(s);
  return j;
}

void run(const Options& o) {
  ConfigMap m = o.common.config_map();
  m["segmentation"] = o.segmentation;
  m["axis"] = o.axis;
  m["input"] = o.input;
  measure::OrientationConfig cfg;
  apply_config(cfg, m, "--set");
  measure::validate(cfg, "--set");
  std::unique_ptr<Detector2D> detector;
  std::string boxes;
  if (o.boxes == "board") {
    detector = std::make_unique<pipeline::potato::BoardBlobDetector>();
    boxes = "BoardBlobDetector on the RGB image";
  } else {
    detector = pipeline::potato::make_detector(pipeline::potato::spec_config({.preset = o.detector_config}).detector,
                                               o.detector_config);
    boxes = "the " + o.detector_config + " preset's detector on the RGB image";
  }
  const auto e =
      pipeline::potato::evaluate_orientation(pipeline::potato::list_orientation_shots(o.rgb, o.depth), *detector, cfg);
  nlohmann::json j = to_json(e.all);
  j["segmentation"] = o.segmentation;
  j["axis"] = o.axis;
  j["input"] = o.input;
  j["ms_per_potato"] = json_number(e.ms_per_potato);
  j["per_light"] = groups(e.per_light);
  j["per_angle"] = groups(e.per_angle);
  j["per_potato"] = groups(e.per_potato);
  j["boxes"] = boxes;
  j["rule"] = "absolute error modulo 180 deg; a shot without box or mask counts 90 deg";
  if (o.shots) {
    nlohmann::json list = nlohmann::json::array();
    for (std::size_t i = 0; i < e.samples.size(); ++i) {
      const auto& s = e.samples[i];
      list.push_back({{"file", s.file},
                      {"potato", s.potato},
                      {"light", s.light},
                      {"truth_deg", json_number(s.truth_deg)},
                      {"ok", s.ok},
                      {"estimate_deg", json_number(s.estimate_deg)},
                      {"error_deg", json_number(e.errors_deg[i])},
                      {"ms", json_number(s.ms)}});
    }
    j["shots"] = std::move(list);
  }
  if (o.common.json) {
    print_json(j);
    return;
  }
  std::printf("%s + %s on %s: MAE %.2f deg, std %.2f deg, max %.2f deg, %d/%d failed, %.2f ms per potato\n",
              o.segmentation.c_str(), o.axis.c_str(), o.input.c_str(), e.all.mae_deg, e.all.std_deg, e.all.max_deg,
              e.all.failures, e.all.count, e.ms_per_potato);
  for (const auto* g : {&e.per_light, &e.per_angle, &e.per_potato})
    for (const auto& s : *g)
      std::printf("  %-8s n=%d MAE %.2f std %.2f\n", s.key.c_str(), s.count, s.mae_deg, s.std_deg);
  if (!o.shots) return;
  for (std::size_t i = 0; i < e.samples.size(); ++i) {
    const auto& s = e.samples[i];
    if (s.ok)
      std::printf("  potato %d %-5s truth %5.1f estimate %5.1f error %5.1f deg  %s\n", s.potato, s.light.c_str(),
                  s.truth_deg, s.estimate_deg, e.errors_deg[i], s.file.c_str());
    else
      std::printf("  potato %d %-5s truth %5.1f no estimate (counted %.0f deg)  %s\n", s.potato, s.light.c_str(),
                  s.truth_deg, e.errors_deg[i], s.file.c_str());
  }
}

}  // namespace eval_potato_orientation_cmd

void add_eval_potato_orientation(CLI::App& eval) {
  using namespace eval_potato_orientation_cmd;
  auto o = std::make_shared<Options>();
  auto* cmd = eval.add_subcommand("potato-orientation", "Potato orientation error on <angle>_<light>_rgb folders");
  cmd->add_option("--color", o->rgb, "Folder with <angle>_<light>_rgb/imageN.png")->required();
  add_deprecated_option(cmd, "--rgb", o->rgb, "--color");
  cmd->add_option("--depth", o->depth, "Folder with <angle>_<light>_depth/imageN.png (colourised depth)")->required();
  cmd->add_option("--segmentation", o->segmentation, "canny | kmeans | ours")->capture_default_str();
  cmd->add_option("--axis", o->axis, "pca | ellipse")->capture_default_str();
  cmd->add_option("--modality", o->input, "rgb | depth: the image the orientation is estimated from")
      ->capture_default_str();
  add_deprecated_option(cmd, "--input", o->input, "--modality");
  cmd->add_option("--boxes", o->boxes,
                  "Box source: board (BoardBlobDetector: one colour blob on a white board) | detector (the "
                  "--detector-config preset's detector, the paper's protocol)")
      ->check(CLI::IsMember({"detector", "board"}))
      ->capture_default_str();
  cmd->add_option("--detector-config", o->detector_config, "Potato preset (or YAML) whose detector gives the boxes")
      ->capture_default_str();
  cmd->add_flag("--shots", o->shots, "Also list each shot: file, potato, light, truth, estimate, error (deg)");
  add_json_flag(cmd, o->common);
  add_config_options(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
