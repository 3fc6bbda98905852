// The broccoli chapter's opening: detections over a few frames, then AP, map, size and time from
// the tracking evaluation of the same pass (what `eval broccoli --track --json` prints).
#include "cropsight/core/error.hpp"
#include "cropsight/report/demo_page.hpp"
#include "number_format.hpp"
#include "section_files.hpp"

namespace cropsight::report {

SystemSummary broccoli_summary(const pipeline::broccoli::TrackingFigures& f, BroccoliReportData& d,
                               const std::filesystem::path& dir) {
  using detail::format_number;
  if (d.overlays.empty()) throw Error(d.sequence, "the broccoli pass kept no overlay frame");
  SystemSummary s;
  s.picture_pngs = std::move(d.overlays);
  d.overlays.clear();
  s.caption =
      "Depth with the detected heads: green = confirmed by the temporal filter, red = not confirmed, magenta "
      "= a confirmed head this frame missed, predicted by the filter; white outlines = the simulator's heads.";
  double ms = d.tracking_ms;
  for (const auto& st : d.stages) ms += st.total_ms;
  s.figures = {
      {"AP50, visible heads: single frame / with the temporal filter (online)",
       format_number(f.ap50_single_frame_visible, "%.3f") + " / " + format_number(f.ap50_online_visible, "%.3f")},
      {"field map precision / recall (" + std::to_string(f.map_heads) + " heads mapped, " +
           std::to_string(f.map_true_heads) + " true)",
       format_number(f.map_precision, "%.3f") + " / " + format_number(f.map_recall, "%.3f")},
      {"head size, mean absolute difference (" + f.size_estimator + ", " + std::to_string(f.head_size.n) + " heads)",
       format_number(f.head_size.mad_mm, "%.1f mm")},
      {"per frame, detector + sizing + tracking, " + std::to_string(d.frames) + " frames",
       format_number(d.frames > 0 ? ms / double(d.frames) : 0.0, "%.1f ms")}};
  s.note =
      "A simulated UK-like pass with a seed the shipped model never saw (docs/simulator.md); the figures on "
      "held-out passes are in docs/pipelines/broccoli-heads.md and broccoli-sizing-tracking.md. The sections "
      "below are the full broccoli report of this pass.";
  s.commands = detail::section_commands(
      dir, {"cropsight simulate broccoli --variety uk --out DIR/seq",
            "cropsight eval broccoli --data DIR/seq --model models/broccoli-oes-general.json --track --json"});
  return s;
}

}  // namespace cropsight::report
