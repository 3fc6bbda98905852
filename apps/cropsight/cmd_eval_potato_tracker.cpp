// cropsight eval potato-tracker (§3.4): which OpenCV tracker continues the potato target
// when detection misses it, measured on simulated approaches by
// pipeline::potato::evaluate_visual_tracker. This file parses, calls and prints.
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/config.hpp"
#include "cropsight/pipeline/potato/visual_tracker_eval.hpp"

namespace cropsight::cli {
namespace eval_potato_tracker_cmd {

struct Options {
  std::vector<std::string> data;
  std::vector<std::string> trackers{"csrt", "kcf", "mil"};
  pipeline::potato::VisualTrackerTrialConfig trial;
  CommonOptions common;
};

tracking::VisualTrackerKind parse_tracker(const std::string& name) {
  tracking::VisualTrackerKind kind{};
  cropsight::detail::parse_value("--trackers", "tracker", name, kind);
  return kind;
}

void run(const Options& o) {
  namespace pp = pipeline::potato;
  std::vector<tracking::VisualTrackerKind> kinds;
  for (const auto& t : o.trackers) kinds.push_back(parse_tracker(t));
  std::vector<pp::TruthSequence> sequences;
  for (const auto& d : o.data) sequences.push_back(pp::read_truth_sequence(d));
  nlohmann::json rows = nlohmann::json::array();
  for (const auto kind : kinds) {
    const pp::VisualTrackerEvaluation e = pp::evaluate_visual_tracker(kind, sequences, o.trial);
    if (o.common.json) {
      rows.push_back({{"tracker", config_name(kind)},
                      {"trials", e.trials},
                      {"updates", e.updates},
                      {"gave_up", e.gave_up},
                      {"mean_iou", json_number(e.mean_iou)},
                      {"success_rate", json_number(e.success_rate)},
                      {"end_success_rate", json_number(e.end_success_rate)},
                      {"first_init_ms", json_number(e.first_init_ms)},
                      {"init_ms", json_number(e.init_ms)},
                      {"init_ms_max", json_number(e.init_ms_max)},
                      {"update_ms", json_number(e.update_ms)},
                      {"update_ms_max", json_number(e.update_ms_max)}});
    } else {
      std::printf(
          "%-4s %d trials, %d scored updates: mean IoU %.3f, success %.1f %% (at the horizon %.1f %%), gave up %d; "
          "CPU ms: init %.2f (max %.2f, first %.2f), update %.2f (max %.2f)\n",
          config_name(kind).c_str(), e.trials, e.updates, e.mean_iou, 100 * e.success_rate, 100 * e.end_success_rate,
          e.gave_up, e.init_ms, e.init_ms_max, e.first_init_ms, e.update_ms, e.update_ms_max);
    }
  }
  if (o.common.json)
    print_json({{"sequences", o.data.size()},
                {"horizon", o.trial.horizon},
                {"stride", o.trial.stride},
                {"success_iou", o.trial.success_iou},
                {"csrt_template_size", o.trial.csrt.template_size},
                {"csrt_scales", o.trial.csrt.scales},
                {"csrt_segmentation", o.trial.csrt.segmentation},
                {"csrt_admm_iterations", o.trial.csrt.admm_iterations},
                {"trackers", rows}});
}

}  // namespace eval_potato_tracker_cmd

void add_eval_potato_tracker(CLI::App& eval) {
  using namespace eval_potato_tracker_cmd;
  auto o = std::make_shared<Options>();
  auto* cmd = eval.add_subcommand(
      "potato-tracker",
      "Which visual tracker continues the potato target without detections: trials on simulated approaches");
  cmd->add_option("--data", o->data, "Simulated sequence folders, comma separated (cropsight simulate potato)")
      ->required()
      ->delimiter(',');
  cmd->add_option("--trackers", o->trackers, "trackers to compare (csrt, kcf, mil)")->delimiter(',');
  cmd->add_option("--horizon", o->trial.horizon, "updates per trial without detection (the paper's TRACKING_LIM)")
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--stride", o->trial.stride, "frames between trial starts")->check(CLI::Range(1, 1000));
  cmd->add_option("--success-iou", o->trial.success_iou, "IoU with the true box that counts as on target")
      ->check(CLI::Range(0.01, 1.0));
  cmd->add_option("--min-visible-pixels", o->trial.min_visible_pixels,
                  "visible pixels of the target for a start and a scored update")
      ->check(CLI::Range(1, 10000000));
  cmd->add_option("--csrt-template-size", o->trial.csrt.template_size,
                  "px; CSRT's template side (tracking.csrt_template_size)")
      ->check(CLI::Range(16, 1000));
  cmd->add_option("--csrt-scales", o->trial.csrt.scales, "CSRT's scale-filter scales (tracking.csrt_scales)")
      ->check(CLI::Range(1, 200));
  cmd->add_option("--csrt-segmentation", o->trial.csrt.segmentation,
                  "true|false; CSRT's colour-histogram mask (tracking.csrt_segmentation)");
  cmd->add_option("--csrt-admm-iterations", o->trial.csrt.admm_iterations,
                  "CSRT's ADMM iterations per frame (tracking.csrt_admm_iterations)")
      ->check(CLI::Range(1, 100));
  add_json_flag(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
