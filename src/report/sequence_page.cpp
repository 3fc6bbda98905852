#include "cropsight/report/sequence_page.hpp"

#include <algorithm>
#include <cstdio>

#include "cropsight/report/render.hpp"
#include "cropsight/report/svg_plot.hpp"
#include "number_format.hpp"

namespace cropsight::report {

using detail::format_number;

std::vector<int> evenly_spaced_frames(int frames, int count) {
  std::vector<int> out;
  if (frames <= 0 || count <= 0) return out;
  if (count == 1) return {0};
  for (int k = 0; k < count; ++k) {
    const int i = int((long(k) * (frames - 1) + (count - 1) / 2) / (count - 1));
    if (out.empty() || out.back() != i) out.push_back(i);
  }
  return out;
}

namespace {

// The sequence's files and the figures it adds up to, with the truth's attributes.
void summary_section(HtmlPage& page, const io::SequenceReader& reader, const SequenceSummary& s) {
  const CameraIntrinsics& cam = s.info.camera;
  page.section("Sequence summary", HtmlPage::Part::Data);
  std::vector<std::pair<std::string, std::string>> rows = {
      {"directory", s.info.dir.string()},
      {"frames", std::to_string(s.info.frames)},
      {"resolution", std::to_string(cam.width) + " x " + std::to_string(cam.height)},
      {"valid depth fraction (mean over frames)", format_number(s.valid_depth_fraction, "%.4f")},
      {"depth range (m)", format_number(s.depth_min_m, "%.3f") + " .. " + format_number(s.depth_max_m, "%.3f")},
      {"ground-truth instances", std::to_string(s.instances)},
      {"colour", s.info.has_color ? "yes" : "no"},
      {"labels", s.info.has_labels ? "yes" : "no"},
      {"camera poses", s.info.has_poses ? "yes" : "no"},
  };
  if (s.info.has_labels) rows.push_back({"labelled pixel fraction (mean)", format_number(s.labelled_fraction, "%.4f")});
  for (const auto& [k, v] : reader.groundtruth().attributes) rows.push_back({"truth: " + k, v});
  page.key_values(rows);
}

// The intrinsics, and per frame the valid depth fraction (and visible instances).
void camera_section(HtmlPage& page, const SequenceSummary& s) {
  const CameraIntrinsics& cam = s.info.camera;
  page.section("Camera", HtmlPage::Part::Data);
  std::string distortion;
  for (double d : cam.distortion) distortion += (distortion.empty() ? "" : ", ") + format_number(d, "%.6g");
  page.key_values({{"sensor", cam.sensor.empty() ? "(unspecified)" : cam.sensor},
                   {"fx, fy (px)", format_number(cam.fx, "%.3f") + ", " + format_number(cam.fy, "%.3f")},
                   {"cx, cy (px)", format_number(cam.cx, "%.3f") + ", " + format_number(cam.cy, "%.3f")},
                   {"depth scale (m per unit)", format_number(cam.depth_scale, "%.6g")},
                   {"distortion", distortion.empty() ? "none" : distortion}});

  std::vector<double> xs;
  for (int i = 0; i < s.info.frames; ++i) xs.push_back(i);
  std::vector<Series> series = {{"valid depth", xs, s.valid_depth_per_frame, "#2a7"}};
  if (!s.visible_instances_per_frame.empty()) {
    PlotOptions po{"Visible ground-truth instances per frame", "frame", "instances", 560, 260, true};
    std::vector<double> ys(s.visible_instances_per_frame.begin(), s.visible_instances_per_frame.end());
    page.svg(svg_line_plot(series, {"Valid depth fraction per frame", "frame", "fraction", 560, 260, true}));
    page.svg(svg_line_plot({{"visible instances", xs, ys, "#c52"}}, po));
  } else {
    page.svg(svg_line_plot(series, {"Valid depth fraction per frame", "frame", "fraction", 560, 260, true}));
  }
}

// Evenly spaced frames: depth (one colour range for all), colour and labels.
void frames_section(HtmlPage& page, const io::SequenceReader& reader, const SequenceSummary& s,
                    const SequencePageOptions& o) {
  const CameraIntrinsics& cam = s.info.camera;
  page.section("Frames", HtmlPage::Part::Data);
  const std::vector<int> shown = evenly_spaced_frames(s.info.frames, o.frames_shown);
  const int factor = std::max(1, (o.min_display_width + cam.width - 1) / cam.width);
  DepthRange range{s.depth_min_m, s.depth_max_m};
  if (!shown.empty()) {
    // The sequence-wide min/max is sensitive to flying pixels; the robust range of a frame is
    // not, so use it when it lies inside the sequence range.
    const RgbdFrame first = reader.read(shown.front());
    const DepthRange r = robust_depth_range(first.depth, cam.depth_scale);
    if (r.near_m >= s.depth_min_m && r.far_m <= s.depth_max_m) range = r;
  }
  page.paragraph("Depth colour map: near = red, far = blue, black = no return; the same range, " +
                 format_number(range.near_m, "%.3f") + " .. " + format_number(range.far_m, "%.3f") +
                 " m, for every frame shown (2nd-98th percentile of the first one)." +
                 (s.info.has_labels ? " White outlines: ground-truth instances." : ""));
  for (int i : shown) {
    const RgbdFrame f = reader.read(i);
    std::vector<Figure> row;
    ColorImage depth = depth_colormap(f.depth, cam.depth_scale, range);
    if (!f.labels.empty()) draw_label_outlines(depth, f.labels);
    row.push_back(make_figure(upscale(depth, factor), "frame " + std::to_string(i) + ": depth"));
    if (!f.color.empty())
      row.push_back(make_figure(upscale(f.color, factor), "frame " + std::to_string(i) + ": colour"));
    if (!f.labels.empty())
      row.push_back(make_figure(upscale(label_colormap(f.labels), factor), "frame " + std::to_string(i) + ": labels"));
    page.heading("Frame " + std::to_string(i) +
                 (f.camera_position ? " (camera at x = " + format_number(f.camera_position->x(), "%.3f") + " m)" : ""));
    page.figures(row);
  }
}

// The first o.max_instances_listed ground-truth instances, in the field frame.
void truth_section(HtmlPage& page, const io::SequenceReader& reader, const SequencePageOptions& o) {
  const auto& inst = reader.groundtruth().instances;
  if (!inst.empty()) {
    page.section("Ground truth", HtmlPage::Part::Data);
    std::vector<std::vector<std::string>> trows;
    for (std::size_t k = 0; k < inst.size() && int(k) < o.max_instances_listed; ++k) {
      const auto& t = inst[k];
      std::string extra;
      for (const auto& [name, v] : t.extra)
        extra += (extra.empty() ? "" : ", ") + name + "=" + format_number(v, "%.4g");
      trows.push_back({std::to_string(t.id), format_number(t.position.x(), "%.3f"),
                       format_number(t.position.y(), "%.3f"), format_number(t.position.z(), "%.3f"),
                       format_number(t.diameter_mm, "%.1f"), extra});
    }
    page.table({"id", "x (m)", "y (m)", "z (m)", "diameter (mm)", "other"}, trows,
               inst.size() > trows.size() ? "first " + std::to_string(trows.size()) + " of " +
                                                std::to_string(inst.size()) + " instances (field frame)"
                                          : "field frame positions");
  }
}

}  // namespace

void add_sequence_sections(HtmlPage& page, const io::SequenceReader& reader, const SequenceSummary& s,
                           const SequencePageOptions& o) {
  summary_section(page, reader, s);
  camera_section(page, s);
  frames_section(page, reader, s, o);
  truth_section(page, reader, o);
}

}  // namespace cropsight::report
