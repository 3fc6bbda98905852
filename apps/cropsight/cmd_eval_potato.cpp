// cropsight eval potato: the whole harvest loop (pipeline::potato::Pipeline from the preset) on a
// simulated approach (`cropsight simulate potato`), scored against the simulator's truth by
// pipeline::potato::evaluate_potato_sequence. This file parses, builds, calls and prints.
#include <cstdio>

#include "commands.hpp"
#include "cropsight/pipeline/potato/eval.hpp"
#include "potato_cli.hpp"

namespace cropsight::cli {
namespace eval_potato_cmd {

struct Options {
  CommonOptions common;
  std::string data;
  double min_iou = 0.3;
  bool frames = false;
};

nlohmann::json frames_json(const pipeline::potato::SequenceEvaluation& r) {
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& s : r.figures.per_frame) {
    const auto& fr = r.run[std::size_t(s.frame)];
    const auto& t = fr.target;
    nlohmann::json j{{"frame", s.frame},
                     {"state", config_name(t.state)},
                     {"target_id", t.target_id},
                     {"potato", s.potato},
                     {"on_target", s.on_target},
                     {"iou", json_number(s.iou)},
                     {"true_z_m", json_number(s.true_z_m)}};
    j["cut"] = s.cut;
    if (s.positioned)
      j["error_mm"] = {json_number(s.error_mm.x()), json_number(s.error_mm.y()), json_number(s.error_mm.z())};
    if (s.angle_error_deg >= 0) j["angle_error_deg"] = json_number(s.angle_error_deg);
    nlohmann::json dets = nlohmann::json::array();
    for (std::size_t i = 0; i < fr.detections.size(); ++i) {
      const auto& d = fr.detections[i];
      dets.push_back({{"box", {json_number(d.x1), json_number(d.y1), json_number(d.x2), json_number(d.y2)}},
                      {"score", json_number(d.score)},
                      {"surface_depth_m", json_number(fr.positions[i].surface_depth_m)},
                      {"depth_ok", fr.positions[i].depth_ok}});
    }
    j["detections"] = dets;
    rows.push_back(j);
  }
  return rows;
}

nlohmann::json axis_json(const pipeline::potato::AxisError& a) {
  return {{"mean_mm", json_number(a.mean_mm)}, {"mae_mm", json_number(a.mae_mm)}, {"std_mm", json_number(a.std_mm)}};
}

void run(const Options& o) {
  namespace pp = pipeline::potato;
  const auto built = make_potato(o.common);
  pp::Pipeline& pipeline = *built;
  const pp::SequenceEvaluation r = pp::evaluate_potato_sequence(pipeline, o.data, o.min_iou);
  const pp::Figures& e = r.figures;
  const pp::StageTimes& t = r.ms;
  if (o.common.json) {
    nlohmann::json j{
        {"frames", e.frames},
        {"frames_with_target", e.frames_with_target},
        {"frames_matched", e.frames_matched},
        {"frames_on_target", e.frames_on_target},
        {"frames_positioned", e.frames_positioned},
        {"frames_cut", e.frames_cut},
        {"targets", e.targets},
        {"target_switches", e.target_switches},
        {"lost_events", e.lost_events},
        {"position", {{"x", axis_json(e.x)}, {"y", axis_json(e.y)}, {"z", axis_json(e.z)}}},
        {"position_cut", {{"x", axis_json(e.cut_x)}, {"y", axis_json(e.cut_y)}, {"z", axis_json(e.cut_z)}}},
        {"length_mae_mm", json_number(e.length_mae_mm)},
        {"width_mae_mm", json_number(e.width_mae_mm)},
        {"angle_mae_deg", json_number(e.angle_mae_deg)},
        {"angles", e.angles},
        {"angle_mae_full_view_deg", json_number(e.angle_mae_full_view_deg)},
        {"angles_full_view", e.angles_full_view},
        {"ms_per_frame",
         {{"detect", json_number(t.detect)},
          {"locate", json_number(t.locate)},
          {"track", json_number(t.track)},
          {"orient", json_number(t.orient)},
          {"total", json_number(t.total)},
          {"max", json_number(t.max_total)}}}};
    if (o.frames) j["per_frame"] = frames_json(r);
    print_json(j);
    return;
  }
  std::printf(
      "%d frames: a target in %d (%d on the simulator's target), %d positioned in full view, %d cut by the "
      "border; %d target(s), %d switch(es), %d lost\n",
      e.frames, e.frames_with_target, e.frames_on_target, e.frames_positioned, e.frames_cut, e.targets,
      e.target_switches, e.lost_events);
  for (const auto& [name, a] : {std::pair{"x", e.x}, std::pair{"y", e.y}, std::pair{"z", e.z}})
    std::printf("position %s (full view): mean %+.2f  MAE %.2f  std %.2f mm\n", name, a.mean_mm, a.mae_mm, a.std_mm);
  std::printf(
      "size MAE: length %.2f mm, width %.2f mm; angle MAE %.2f deg (%d frames; %.2f deg over the %d in full "
      "view)\n",
      e.length_mae_mm, e.width_mae_mm, e.angle_mae_deg, e.angles, e.angle_mae_full_view_deg, e.angles_full_view);
  std::printf("ms per frame: detect %.2f  locate %.2f  track %.2f  orient %.2f  total %.2f (max %.2f)\n", t.detect,
              t.locate, t.track, t.orient, t.total, t.max_total);
}

}  // namespace eval_potato_cmd

void add_eval_potato(CLI::App& eval) {
  using namespace eval_potato_cmd;
  auto o = std::make_shared<Options>();
  auto* cmd = eval.add_subcommand(
      "potato", "The harvest loop on a simulated approach, scored against the simulator's truth (position, tracking)");
  cmd->add_option("--data", o->data, "simulated sequence folder (cropsight simulate potato)")->required();
  cmd->add_flag("--per-frame", o->frames, "With --json: a row per frame (matched potato, errors)");
  add_deprecated_flag(cmd, "--frames", o->frames, "--per-frame");
  cmd->add_option("--min-iou", o->min_iou, "IoU of the target's box with a simulated potato's visible box to match")
      ->check(CLI::Range(0.01, 1.0));
  add_config_options(cmd, o->common);
  add_json_flag(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
