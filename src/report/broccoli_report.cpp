#include "cropsight/report/broccoli_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>
#include <unordered_map>

#include "cropsight/report/svg_charts.hpp"
#include "cropsight/report/svg_plot.hpp"
#include "number_format.hpp"

namespace cropsight::report {

std::vector<double> coco_thresholds() {
  std::vector<double> t;
  for (int i = 0; i < 10; ++i) t.push_back(0.5 + 0.05 * i);
  return t;
}

namespace {

// A detection with the IoU of every truth it overlaps.
struct Det {
  float score;
  std::size_t frame, index;
  std::vector<std::pair<int, double>> ious;  // truth index, IoU (descending IoU)
};

// IoU of every (detection, truth) pair that overlaps, once; each frame's detections in score
// order (stable). Adds the number of truths to `num_truth`.
std::vector<std::vector<Det>> overlaps(const std::vector<PrFrame>& frames, std::int64_t& num_truth) {
  std::vector<std::vector<Det>> per_frame(frames.size());
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const auto& fr = frames[f];
    num_truth += std::int64_t(fr.truth.size());
    std::unordered_map<int, int> owner;
    for (std::size_t t = 0; t < fr.truth.size(); ++t)
      for (int i : fr.truth[t]) owner[i] = int(t);
    for (std::size_t d = 0; d < fr.detections.size(); ++d) {
      std::unordered_map<int, int> inter;
      for (int i : fr.detections[d].indices) {
        auto it = owner.find(i);
        if (it != owner.end()) ++inter[it->second];
      }
      Det det{fr.detections[d].score, f, d, {}};
      for (const auto& [t, n] : inter) {
        const double uni = double(fr.detections[d].indices.size() + fr.truth[std::size_t(t)].size()) - n;
        det.ious.emplace_back(t, uni > 0 ? n / uni : 0.0);
      }
      std::sort(det.ious.begin(), det.ious.end(), [](const auto& a, const auto& b) {
        return a.second > b.second || (a.second == b.second && a.first < b.first);
      });
      per_frame[f].push_back(std::move(det));
    }
    std::stable_sort(per_frame[f].begin(), per_frame[f].end(),
                     [](const Det& a, const Det& b) { return a.score > b.score; });
  }
  return per_frame;
}

// Global ranking (score descending; ties by frame then input order).
std::vector<const Det*> ranking(const std::vector<std::vector<Det>>& per_frame) {
  std::vector<const Det*> ranked;
  for (const auto& v : per_frame)
    for (const auto& d : v) ranked.push_back(&d);
  std::stable_sort(ranked.begin(), ranked.end(), [](const Det* a, const Det* b) {
    if (a->score != b->score) return a->score > b->score;
    if (a->frame != b->frame) return a->frame < b->frame;
    return a->index < b->index;
  });
  return ranked;
}

// Whether each detection is correct at IoU threshold t: per frame in score order, its best truth
// not yet matched decides.
std::unordered_map<const Det*, bool> correct_at(const std::vector<std::vector<Det>>& per_frame, double t) {
  std::unordered_map<const Det*, bool> correct;
  for (const auto& v : per_frame) {
    std::vector<char> used(64, 0);
    for (const auto& d : v) {
      bool ok = false;
      for (const auto& [truth, iou] : d.ious) {
        if (std::size_t(truth) >= used.size()) used.resize(std::size_t(truth) + 1, 0);
        if (used[std::size_t(truth)]) continue;
        if (iou >= t) {
          used[std::size_t(truth)] = 1;
          ok = true;
        }
        break;  // the best unmatched truth decides
      }
      correct[&d] = ok;
    }
  }
  return correct;
}

// Precision and recall down the ranking, and AP as the area under the precision envelope.
PrCurve pr_curve(double t, const std::vector<const Det*>& ranked, std::unordered_map<const Det*, bool>& correct,
                 std::int64_t num_truth) {
  PrCurve c;
  c.iou = t;
  std::int64_t tp = 0;
  for (std::size_t i = 0; i < ranked.size(); ++i) {
    tp += correct[ranked[i]] ? 1 : 0;
    c.recall.push_back(num_truth ? double(tp) / double(num_truth) : NAN);
    c.precision.push_back(double(tp) / double(i + 1));
  }
  if (num_truth == 0) {
    c.ap = NAN;
  } else {
    double ap = 0, prev_r = 0, pmax = 0;
    std::vector<double> env(c.precision.size());
    for (std::size_t i = c.precision.size(); i-- > 0;) env[i] = pmax = std::max(pmax, c.precision[i]);
    for (std::size_t i = 0; i < c.recall.size(); ++i) {
      ap += (c.recall[i] - prev_r) * env[i];
      prev_r = c.recall[i];
    }
    c.ap = ap;
  }
  return c;
}

}  // namespace

std::vector<PrCurve> pr_curves(const std::vector<PrFrame>& frames, const std::vector<double>& thresholds) {
  std::int64_t num_truth = 0;
  const std::vector<std::vector<Det>> per_frame = overlaps(frames, num_truth);
  const std::vector<const Det*> ranked = ranking(per_frame);
  std::vector<PrCurve> curves;
  for (double t : thresholds) {
    auto correct = correct_at(per_frame, t);
    curves.push_back(pr_curve(t, ranked, correct, num_truth));
  }
  return curves;
}

namespace {

/// A figure of the page's tables: "n/a" where it is undefined (NaN: no truth to score against).
std::string figure(double v, const char* printf_format = "%.3f") {
  return std::isfinite(v) ? detail::format_number(v, printf_format) : "n/a";
}

std::string pr_plot(const std::vector<PrCurve>& curves, const std::string& title) {
  std::vector<Series> series;
  for (std::size_t i = 0; i < curves.size(); ++i) {
    Series s;
    char name[64];
    std::snprintf(name, sizeof name, "IoU %.2f (AP %.2f)", curves[i].iou, curves[i].ap);
    s.name = name;
    // From (0, first precision) so that a curve with few detections is still visible.
    s.x.push_back(0.0);
    s.y.push_back(curves[i].precision.empty() ? 1.0 : curves[i].precision.front());
    s.x.insert(s.x.end(), curves[i].recall.begin(), curves[i].recall.end());
    s.y.insert(s.y.end(), curves[i].precision.begin(), curves[i].precision.end());
    const double k = curves.size() > 1 ? double(i) / double(curves.size() - 1) : 0.0;  // green → purple
    char col[16];
    std::snprintf(col, sizeof col, "#%02x%02x%02x", int(40 + 120 * k), int(160 - 120 * k), int(80 + 120 * k));
    s.color = col;
    series.push_back(std::move(s));
  }
  PlotOptions o;
  o.title = title;
  o.x_label = "recall";
  o.y_label = "precision";
  o.height = 340;
  o.y_from_zero = true;
  return svg_line_plot(series, o);
}

// True heads, the temporal filter's map and the camera path, in the field frame.
void field_map_section(HtmlPage& page, const BroccoliReportData& d) {
  page.section("Field map");
  ScatterSeries truth{"true heads", {}, {}, {}, "#777", true};
  for (const auto& h : d.true_heads) {
    truth.x.push_back(h.x);
    truth.y.push_back(h.y);
    truth.r.push_back(h.diameter_mm / 2000.0);
  }
  ScatterSeries hit{d.has_truth ? "mapped (matched)" : "mapped heads", {}, {}, {}, "#2a7", false};
  ScatterSeries miss{"mapped (no true head within 5 cm)", {}, {}, {}, "#d33", false};
  for (const auto& h : d.map_heads) {
    auto& s = h.matched ? hit : miss;
    s.x.push_back(h.x);
    s.y.push_back(h.y);
    s.r.push_back(h.diameter_mm / 2000.0);
  }
  ScatterSeries cam{"camera", {}, {}, {}, "#36c", false};
  for (const auto& [x, y] : d.camera_path) {
    cam.x.push_back(x);
    cam.y.push_back(y);
    cam.r.push_back(0.004);
  }
  ScatterOptions o;
  o.title = "field map (circle = head diameter)";
  o.x_label = "field x (m, along the row)";
  o.y_label = "field y (m)";
  o.equal_aspect = true;
  o.width = 900;
  o.height = 420;
  // Without ground truth every mapped head is drawn alike, and no empty series fills the legend.
  const std::vector<ScatterSeries> series =
      d.has_truth ? std::vector<ScatterSeries>{truth, cam, hit, miss} : std::vector<ScatterSeries>{cam, hit};
  page.svg(svg_scatter_plot(series, o),
           d.has_truth ? "True heads (grey outlines, visible in at least one frame) and the map of the temporal filter"
                       : "The map of the temporal filter and the camera's path (no ground truth)");
}

// Estimated against true diameters, and the raw estimators' errors against distance from the axis.
void size_section(HtmlPage& page, const BroccoliReportData& d) {
  page.section("Size");
  ScatterSeries s{"heads", {}, {}, {}, "#2a7", false};
  for (const auto& p : d.head_sizes) {
    s.x.push_back(p.truth_mm);
    s.y.push_back(p.estimate_mm);
  }
  ScatterOptions o;
  o.title = "estimated against true diameter, per mapped head";
  o.x_label = "true diameter (mm)";
  o.y_label = "estimated diameter (mm)";
  o.diagonal = true;
  o.width = 420;
  o.height = 420;
  page.svg(svg_scatter_plot({s}, o), "Dashed: estimate = truth");
  ScatterSeries b{"bounding box", {}, {}, {}, "#2a7", false}, h{"convex hull", {}, {}, {}, "#a3c", true};
  for (const auto& e : d.frame_errors) {
    b.x.push_back(e.distance_m);
    b.y.push_back(e.bbox_error_mm);
    h.x.push_back(e.distance_m);
    h.y.push_back(e.hull_error_mm);
  }
  ScatterOptions q;
  q.title = "per-frame size error against distance from the optical axis";
  q.x_label = "distance of the head centroid from the optical axis (m)";
  q.y_label = "raw estimate − truth (mm)";
  page.svg(svg_scatter_plot({b, h}, q), "Raw estimators, before bias correction");
}

// Without ground truth: how the mapped heads' diameters are distributed, 10 mm bins.
void size_distribution_section(HtmlPage& page, const BroccoliReportData& d) {
  page.section("Size");
  std::map<int, int> bins;
  for (const auto& h : d.map_heads)
    if (h.diameter_mm > 0) ++bins[int(h.diameter_mm / 10.0)];
  std::vector<Bar> bars;
  for (const auto& [bin, count] : bins)
    bars.push_back({std::to_string(bin * 10) + "–" + std::to_string(bin * 10 + 10), double(count)});
  if (bars.empty()) {
    page.paragraph("No mapped head was sized.");
    return;
  }
  page.svg(svg_bar_chart(bars, "mapped heads per diameter (mm)", "heads"),
           "Diameters of the field map's heads (" + d.estimator + " estimator, the model's size correction)");
}

// Accepted heads in each frame: where the model sees many, few or none.
void detections_plot(HtmlPage& page, const BroccoliReportData& d) {
  if (d.detections_per_frame.empty()) return;
  Series s;
  s.name = "heads accepted";
  s.color = "#2a7";
  for (std::size_t i = 0; i < d.detections_per_frame.size(); ++i) {
    s.x.push_back(double(i));
    s.y.push_back(double(d.detections_per_frame[i]));
  }
  PlotOptions o;
  o.title = "detections per frame";
  o.x_label = "frame";
  o.y_label = "heads";
  o.height = 220;
  o.y_from_zero = true;
  page.svg(svg_line_plot({s}, o), "Heads the classifier accepted in each frame (before the temporal filter)");
}

// Mean time per frame of each detector stage and of sizing + tracking.
void timing_section(HtmlPage& page, const BroccoliReportData& d) {
  page.section("Timing");
  std::vector<Bar> bars;
  const double n = d.frames > 0 ? double(d.frames) : 1.0;
  for (const auto& s : d.stages) bars.push_back({s.name, s.total_ms / n});
  bars.push_back({"sizing + tracking", d.tracking_ms / n});
  page.svg(svg_bar_chart(bars, "mean milliseconds per frame", "ms"), "Detector stages and the sizing + tracking step");
}

// PR curves of single-frame and tracked detections, and their AP per IoU threshold.
void pr_section(HtmlPage& page, const BroccoliReportData& d) {
  page.section("Precision–recall (IoU 0.50 … 0.95)");
  if (!d.pr_single.empty()) page.svg(pr_plot(d.pr_single, "single-frame detection"), "Every cluster ranked by score");
  if (!d.pr_tracked.empty())
    page.svg(pr_plot(d.pr_tracked, "with the temporal filter (offline, after the pass)"),
             "Detections of heads confirmed by the temporal filter ranked first");
  std::vector<std::vector<std::string>> rows;
  for (std::size_t i = 0; i < d.pr_single.size(); ++i)
    rows.push_back({figure(d.pr_single[i].iou, "%.2f"), figure(d.pr_single[i].ap),
                    i < d.pr_tracked.size() ? figure(d.pr_tracked[i].ap) : "n/a"});
  page.table({"IoU", "AP single frame", "AP temporal filter (offline, after the pass)"}, rows);
}

}  // namespace

void add_broccoli_sections(HtmlPage& page, const BroccoliReportData& d) {
  // The result in the order a reader asks for it: what was detected in the frames, the map it
  // adds up to, the sizes, the time it took; then the figures against ground truth. The
  // sequence's own summary (sequence_page.hpp) is the page's data part and follows all of this.
  page.section("Broccoli heads: detections over frames");
  page.paragraph("Sequence " + d.sequence + ", model " + d.model + ", " + std::to_string(d.frames) +
                 " frames. Size estimator: " + d.estimator + "." +
                 (d.has_truth ? "" : " The sequence has no ground truth: what the pipeline found, no metric."));
  if (!d.overlays.empty()) {
    page.paragraph(
        std::string("Depth with detections: green = head confirmed by the temporal filter, red = not confirmed, "
                    "magenta = a confirmed head this frame missed, predicted by the filter "
                    "(tracking.predict_missed)") +
        (d.has_truth ? "; white outlines = ground-truth heads." : "."));
    page.figures(d.overlays);
  }
  detections_plot(page, d);
  field_map_section(page, d);
  if (d.has_truth)
    size_section(page, d);
  else
    size_distribution_section(page, d);
  timing_section(page, d);
  page.section("Key figures");
  page.key_values(d.metrics, d.has_truth ? "Map and size metrics per head; ap50 per frame and point set"
                                         : "Counts over the pass (no ground truth, so no metric)");
  if (d.has_truth) pr_section(page, d);
}

}  // namespace cropsight::report
