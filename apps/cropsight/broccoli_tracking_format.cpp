// The broccoli tracking figures (map, sizes, temporal AP) as JSON and text for `eval broccoli
// --track`; nothing is computed here.
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

}  // namespace

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
    if (f.head_bbox_fit) fit["mapped_heads"]["bbox"] = fit_json("bbox", *f.head_bbox_fit);
    if (f.head_hull_fit) fit["mapped_heads"]["hull"] = fit_json("hull", *f.head_hull_fit);
    j["size_bias_fit"] = fit;
  }
  return j;
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
