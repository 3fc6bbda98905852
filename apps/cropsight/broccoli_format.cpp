// Formatting of the broccoli library results for the CLI (text and JSON); nothing is computed here.
#include <cmath>
#include <cstdio>

#include "broccoli_cli.hpp"

namespace cropsight::cli {

namespace {

nlohmann::json size_json(const eval::SizeMetrics& m) {
  return {{"n", m.n},
          {"mede_mm", json_number(m.mede_mm)},
          {"mad_mm", json_number(m.mad_mm)},
          {"medae_mm", json_number(m.medae_mm)},
          {"pearson_r", json_number(m.pearson_r)},
          {"rmse_mm", json_number(m.rmse_mm)}};
}

nlohmann::json fit_json(const std::string& name, const measure::BiasFit& f) {
  return {{"scale", f.scale},
          {"offset_mm", f.offset_mm},
          {"n", f.n},
          {"rms_before_mm", f.rms_before_mm},
          {"rms_after_mm", f.rms_after_mm},
          {"set", "sizing." + name + "_scale=" + std::to_string(f.scale) + " sizing." + name +
                      "_offset_mm=" + std::to_string(f.offset_mm)}};
}

nlohmann::json num_or_null(double v, bool valid) { return valid ? json_number(v) : nlohmann::json(nullptr); }
}  // namespace

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

nlohmann::json tracking_json(const pipeline::broccoli::TrackingFigures& f) {
  nlohmann::json j;
  const double nan = NAN;
  if (!f.map_aligned)
    j["map_note"] = "a sequence has no poses.csv: the map cannot be placed in the truth's field frame";
  j["map_precision"] = json_number(f.map_aligned ? f.map_precision : nan);
  j["map_precision_visible"] = json_number(f.map_aligned ? f.map_precision_visible : nan);
  j["map_recall"] = json_number(f.map_aligned ? f.map_recall : nan);
  j["duplicate_rate"] = json_number(f.map_aligned ? f.duplicate_rate : nan);
  j["count_error"] = f.count_error;
  j["count_error_rel"] = json_number(f.count_error_rel);
  j["map_heads"] = f.map_heads;
  j["map_true_heads"] = f.map_true_heads;
  j["map_matched"] = f.map_matched;
  j["map_ignored"] = f.map_ignored;
  j["map_mean_distance_m"] = json_number(f.map_mean_distance_m);
  j["map_min_visible_points"] = f.map_min_visible_points;
  j["size_estimator"] = f.size_estimator;
  j["size_mede_mm"] = json_number(f.head_size.mede_mm);
  j["size_mad_mm"] = json_number(f.head_size.mad_mm);
  j["size_pearson_r"] = json_number(f.head_size.pearson_r);
  j["size_heads"] = f.head_size.n;
  j["size_per_head"] = {{"chosen", size_json(f.head_size)},
                        {"bbox_raw", size_json(f.head_bbox_raw)},
                        {"hull_raw", f.hull_computed ? size_json(f.head_hull_raw) : nlohmann::json(nullptr)}};
  j["size_frame_mede_mm"] = json_number(f.frame_size.mede_mm);
  j["size_frame_mad_mm"] = json_number(f.frame_size.mad_mm);
  j["size_frame_pearson_r"] = json_number(f.frame_size.pearson_r);
  j["size_per_frame"] = {{"chosen", size_json(f.frame_size)},
                         {"bbox_raw", size_json(f.frame_bbox_raw)},
                         {"hull_raw", f.hull_computed ? size_json(f.frame_hull_raw) : nlohmann::json(nullptr)}};
  j["ap50_single_frame"] = json_number(f.ap50_single_frame);
  j["ap50_online"] = json_number(f.ap50_online);
  j["ap50_offline"] = json_number(f.ap50_offline);
  j["ap50_temporal"] = json_number(f.ap50_offline);
  j["map50_95_single_frame"] = json_number(f.map50_95_single_frame);
  j["map50_95_online"] = json_number(f.map50_95_online);
  j["map50_95_offline"] = json_number(f.map50_95_offline);
  j["map50_95_temporal"] = json_number(f.map50_95_offline);
  j["ap50_single_frame_visible"] = json_number(f.ap50_single_frame_visible);
  j["ap50_online_visible"] = json_number(f.ap50_online_visible);
  j["ap50_offline_visible"] = json_number(f.ap50_offline_visible);
  j["tracking_ms_per_frame"] = f.tracking_ms_per_frame;
  if (f.bbox_fit || f.hull_fit) {
    nlohmann::json fit;
    if (f.bbox_fit) fit["bbox"] = fit_json("bbox", *f.bbox_fit);
    if (f.hull_fit) fit["hull"] = fit_json("hull", *f.hull_fit);
    j["size_bias_fit"] = fit;
  }
  return j;
}

nlohmann::json detection_json(const Detection& d, int id) {
  return {{"id", id},
          {"score", d.score},
          {"centroid", {d.centroid.x(), d.centroid.y(), d.centroid.z()}},
          {"box", {d.box.x, d.box.y, d.box.width, d.box.height}},
          {"points", d.indices.size()}};
}

// --track: each head's size and track id, the heads the frame missed (tracking.predict_missed:
// where the filter expects them; their tracks may still fail to reach the map, compare track_id
// with --map) and the camera estimate.
void add_tracking_json(const pipeline::broccoli::FrameResult& r, const tracking::HeadMapper& mapper,
                       nlohmann::json& line) {
  nlohmann::json heads = nlohmann::json::array();
  const auto& measured = mapper.detections();
  const std::size_t first = measured.size() - r.detections.size();
  for (std::size_t k = 0; k < r.detections.size(); ++k) {
    const auto& m = measured[first + k];
    heads.push_back({{"id", int(k) + 1},
                     {"track_id", m.track_id},
                     {"diameter_mm", num_or_null(m.size.diameter_mm, m.size.valid)},
                     {"bbox_mm", num_or_null(m.size.bbox_mm, m.size.valid)},
                     {"hull_mm", num_or_null(m.size.hull_mm, m.size.valid)},
                     {"harvestable", m.size.harvestable},
                     {"field", {m.field_position.x(), m.field_position.y(), m.field_position.z()}}});
  }
  line["heads"] = std::move(heads);
  nlohmann::json predicted = nlohmann::json::array();
  for (const auto& p : r.predicted)
    predicted.push_back({{"track_id", p.track_id},
                         {"points", p.indices.size()},
                         {"centroid", {p.centroid.x(), p.centroid.y(), p.centroid.z()}}});
  line["predicted"] = std::move(predicted);
  const auto& c = r.association.camera_position;
  line["camera_estimate"] = {c.x(), c.y(), c.z()};
}

void print_tracking_summary(const pipeline::broccoli::TrackingFigures& f) {
  const double nan = NAN;
  std::printf("  map: precision %.3f  recall %.3f  duplicates %.3f  count error %+d (%d heads mapped, %d true)\n",
              f.map_aligned ? f.map_precision : nan, f.map_aligned ? f.map_recall : nan,
              f.map_aligned ? f.duplicate_rate : nan, f.count_error, f.map_heads, f.map_true_heads);
  std::printf("  map, heads too little seen ignored: precision %.3f (%d mapped heads at such heads)\n",
              f.map_aligned ? f.map_precision_visible : nan, f.map_ignored);
  std::printf("  map placement: %.1f mm mean distance of a matched head from its true head (field plane)\n",
              1000.0 * f.map_mean_distance_m);
  std::printf("  size (%s, per head): MEDE %.1f mm  MAD %.1f mm  r %.3f  (%d heads)\n", f.size_estimator.c_str(),
              f.head_size.mede_mm, f.head_size.mad_mm, f.head_size.pearson_r, f.head_size.n);
  std::printf("  size per frame: MEDE %.1f mm  MAD %.1f mm  r %.3f\n", f.frame_size.mede_mm, f.frame_size.mad_mm,
              f.frame_size.pearson_r);
  std::printf(
      "  AP50 single frame %.4f  with the temporal filter: online %.4f (at each frame)  offline %.4f (after "
      "the pass)\n",
      f.ap50_single_frame, f.ap50_online, f.ap50_offline);
  std::printf("  AP50 visible heads: single frame %.4f  online %.4f  offline %.4f\n", f.ap50_single_frame_visible,
              f.ap50_online_visible, f.ap50_offline_visible);
  std::printf("  sizing + tracking %.3f ms/frame\n", f.tracking_ms_per_frame);
  for (const auto* fit : {&f.bbox_fit, &f.hull_fit})
    if (*fit)
      std::printf("  size bias fit (%s): --set %s  (RMS %.1f → %.1f mm)\n", fit == &f.bbox_fit ? "bbox" : "hull",
                  fit_json(fit == &f.bbox_fit ? "bbox" : "hull", **fit)["set"].get<std::string>().c_str(),
                  (*fit)->rms_before_mm, (*fit)->rms_after_mm);
}

}  // namespace cropsight::cli
