// The broccoli evaluation's figures (Table I + II) as JSON for `eval broccoli` and `report`;
// nothing is computed here.
#include "broccoli_cli.hpp"

namespace cropsight::cli {

nlohmann::json stages_json(const std::vector<StageMs>& stages) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& s : stages) j[s.name] = s.ms;
  return j;
}

nlohmann::json eval_json(const pipeline::broccoli::Figures& r) {
  const auto& c = r.confusion;
  nlohmann::json j;
  j["frames"] = r.frames;
  j["clusters"] = r.clusters;
  j["truth_heads"] = r.truth_heads;
  j["detections"] = r.detections;
  j["tp"] = c.tp;
  j["fp"] = c.fp;
  j["tn"] = c.tn;
  j["fn"] = c.fn;
  j["accuracy"] = json_number(c.accuracy());
  j["precision"] = json_number(c.precision());
  j["recall"] = json_number(c.recall());
  j["specificity"] = json_number(c.specificity());
  j["npv"] = json_number(c.npv());
  j["f1"] = json_number(c.f1());
  j["kappa"] = json_number(c.kappa());
  j["ap50"] = json_number(r.ap50);
  j["map50_95"] = json_number(r.map50_95);
  j["truth_heads_in_view"] = r.truth_heads_in_view;
  j["ap50_in_view"] = json_number(r.ap50_in_view);
  j["map50_95_in_view"] = json_number(r.map50_95_in_view);
  j["truth_heads_visible"] = r.truth_heads_visible;
  j["ap50_visible"] = json_number(r.ap50_visible);
  j["map50_95_visible"] = json_number(r.map50_95_visible);
  j["truth_heads_any_depth"] = r.truth_heads_any_depth;
  j["ap50_any_depth"] = json_number(r.ap50_any_depth);
  j["truth_heads_visible_any_depth"] = r.truth_heads_visible_any_depth;
  j["ap50_visible_any_depth"] = json_number(r.ap50_visible_any_depth);
  j["fps"] = json_number(r.fps());
  j["ms_per_frame"] = r.ms_per_frame();
  j["stages_ms"] = stages_json(r.stage_ms_per_frame());
  return j;
}

}  // namespace cropsight::cli
