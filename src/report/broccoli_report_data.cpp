#include "cropsight/report/broccoli_report_data.hpp"

#include <cmath>
#include <cstdio>

#include "cropsight/report/render.hpp"

namespace cropsight::report {

namespace {
std::string fixed3(double v) {
  if (!std::isfinite(v)) return "n/a";
  char b[64];
  std::snprintf(b, sizeof b, "%.3f", v);
  return b;
}

std::vector<std::pair<std::string, std::string>> key_figures(const pipeline::broccoli::TrackingFigures& f) {
  auto map_fig = [&](double v) { return f.map_aligned ? fixed3(v) : std::string("n/a"); };
  return {{"map_precision", map_fig(f.map_precision)},
          {"map_precision_visible", map_fig(f.map_precision_visible)},
          {"map_recall", map_fig(f.map_recall)},
          {"duplicate_rate", map_fig(f.duplicate_rate)},
          {"count_error", std::to_string(f.count_error)},
          {"map_heads", std::to_string(f.map_heads)},
          {"map_true_heads", std::to_string(f.map_true_heads)},
          {"size_mede_mm", fixed3(f.head_size.mede_mm)},
          {"size_mad_mm", fixed3(f.head_size.mad_mm)},
          {"size_pearson_r", fixed3(f.head_size.pearson_r)},
          {"size_heads", std::to_string(f.head_size.n)},
          {"ap50_single_frame", fixed3(f.ap50_single_frame)},
          {"ap50_online", fixed3(f.ap50_online)},
          {"ap50_offline", fixed3(f.ap50_offline)},
          {"map50_95_single_frame", fixed3(f.map50_95_single_frame)},
          {"map50_95_online", fixed3(f.map50_95_online)},
          {"map50_95_offline", fixed3(f.map50_95_offline)},
          {"tracking_ms_per_frame", fixed3(f.tracking_ms_per_frame)}};
}

Figure overlay_figure(const pipeline::broccoli::PassMaterial::Overlay& o) {
  return make_figure(broccoli_overlay(o), "frame " + std::to_string(o.frame));
}
}  // namespace

ColorImage broccoli_overlay(const pipeline::broccoli::PassMaterial::Overlay& o) {
  ColorImage img = depth_colormap(o.depth, o.depth_scale);
  for (const auto& [pixels, mapped] : o.detections)
    for (int i : pixels) {
      auto& p = img.data[std::size_t(i)];
      p = mapped ? Rgb8{uint8_t(p.r / 3), uint8_t(110 + p.g / 2), uint8_t(p.b / 3)}
                 : Rgb8{uint8_t(120 + p.r / 2), uint8_t(p.g / 3), uint8_t(p.b / 3)};
    }
  for (const auto& pixels : o.predicted)
    for (int i : pixels) {
      auto& p = img.data[std::size_t(i)];
      p = Rgb8{uint8_t(200 + p.r / 5), uint8_t(p.g / 4), uint8_t(200 + p.b / 5)};  // magenta: not in the depth colours
    }
  if (!o.labels.data.empty()) draw_label_outlines(img, o.labels);
  return img;
}

BroccoliReportData broccoli_report_data(const pipeline::broccoli::TrackingFigures& figures,
                                        const pipeline::broccoli::PassMaterial& material) {
  BroccoliReportData d;
  d.sequence = material.sequence;
  d.estimator = figures.size_estimator;
  d.frames = figures.frames;
  d.tracking_ms = figures.tracking_ms_per_frame * double(figures.frames);
  d.metrics = key_figures(figures);
  d.pr_single = pr_curves(material.single_frames, coco_thresholds());
  d.pr_tracked = pr_curves(material.offline_frames, coco_thresholds());
  for (const auto& h : material.map_heads) d.map_heads.push_back({h.x, h.y, h.diameter_mm, h.matched});
  for (const auto& h : material.true_heads) d.true_heads.push_back({h.x, h.y, h.diameter_mm, h.matched});
  d.camera_path = material.camera_path;
  for (const auto& [truth, estimate] : material.head_sizes) d.head_sizes.push_back({truth, estimate});
  for (const auto& e : material.frame_errors)
    d.frame_errors.push_back({e.distance_m, e.bbox_error_mm, e.hull_error_mm});
  for (const auto& o : material.overlays) d.overlays.push_back(overlay_figure(o));
  return d;
}

}  // namespace cropsight::report
