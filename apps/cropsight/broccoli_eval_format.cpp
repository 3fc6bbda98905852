// The broccoli evaluation's figures (Table I + II) as JSON for `eval broccoli` and `report`;
// nothing is computed here.
#include <cstdio>

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

void print_eval_summary(const std::string& model, const std::string& data, const pipeline::broccoli::Figures& r) {
  const auto& c = r.confusion;
  const auto ll = [](std::int64_t v) { return static_cast<long long>(v); };
  std::printf("%s on %s: %ld frames, %ld clusters (%lld heads by the majority rule), %lld detections%s\n",
              model.c_str(), data.c_str(), r.frames, r.clusters, ll(c.positives()), ll(r.detections),
              r.detections == 0 ? ": NO DETECTION AT ALL (the model rejected every cluster)" : "");
  std::printf("  operating point (the model's threshold): precision %.4f  recall %.4f  F1 %.4f  kappa %.4f\n",
              c.precision(), c.recall(), c.f1(), c.kappa());
  std::printf("  TP %lld  FP %lld  TN %lld  FN %lld  accuracy %.4f  specificity %.4f  npv %.4f\n", ll(c.tp), ll(c.fp),
              ll(c.tn), ll(c.fn), c.accuracy(), c.specificity(), c.npv());
  std::printf("  AP ranks every candidate cluster by its score, rejected ones included:\n");
  std::printf("  AP50 %.4f  mAP50:95 %.4f  (%lld labelled heads)\n", r.ap50, r.map50_95, ll(r.truth_heads));
  std::printf("  AP50 %.4f  mAP50:95 %.4f  in view (%lld heads not cut by the border)\n", r.ap50_in_view,
              r.map50_95_in_view, ll(r.truth_heads_in_view));
  std::printf("  AP50 %.4f  mAP50:95 %.4f  visible (%lld heads with >= detection.visible_truth_points points)\n",
              r.ap50_visible, r.map50_95_visible, ll(r.truth_heads_visible));
  std::printf(
      "  AP50 %.4f  visible %.4f  at any depth (%lld / %lld heads the sensor measured, in or out of the window)\n",
      r.ap50_any_depth, r.ap50_visible_any_depth, ll(r.truth_heads_any_depth), ll(r.truth_heads_visible_any_depth));
  std::printf("  %.1f fps (%.2f ms/frame, pipeline only)\n", r.fps(), r.ms_per_frame());
}

}  // namespace cropsight::cli
