// The seedling chapter's opening: left view with the detected seedling (green) and the true one
// (white) outlined, the right view, the measured disparity; envelope and eval figures.
#include <algorithm>
#include <cmath>

#include "cropsight/io/image_io.hpp"
#include "cropsight/report/demo_page.hpp"
#include "cropsight/report/render.hpp"
#include "cropsight/report/svg_overlay.hpp"
#include "number_format.hpp"
#include "section_files.hpp"

namespace cropsight::report {

namespace {

namespace fs = std::filesystem;
using detail::format_number;
using detail::number_at;

// The mask's pixels (value > 0) as one instance, so that its inner boundary can be drawn.
LabelImage as_labels(const GrayImage& mask) {
  LabelImage l(mask.width, mask.height);
  for (std::size_t i = 0; i < mask.size(); ++i) l.data[i] = mask.data[i] > 0 ? 1 : 0;
  return l;
}

// The smallest box around the pixels of either mask, [u0, u1] x [v0, v1]; false when both are empty.
struct PixelBox {
  int u0 = 1 << 30, v0 = 1 << 30, u1 = -1, v1 = -1;
  bool empty() const { return u1 < 0; }
};
PixelBox mask_box(const std::vector<const GrayImage*>& masks) {
  PixelBox b;
  for (const GrayImage* m : masks)
    for (int v = 0; v < m->height; ++v)
      for (int u = 0; u < m->width; ++u)
        if (m->at(u, v) > 0)
          b.u0 = std::min(b.u0, u), b.v0 = std::min(b.v0, v), b.u1 = std::max(b.u1, u), b.v1 = std::max(b.v1, v);
  return b;
}

// Mean disparity (px) over the found seedling's pixels that have one: how far the seedling sits
// to the left in the right view.
double mean_disparity(const DepthImage& disparity_x256, const GrayImage& found) {
  double sum = 0;
  int n = 0;
  for (std::size_t i = 0; i < found.size(); ++i)
    if (found.data[i] > 0 && disparity_x256.data[i] > 0) sum += disparity_x256.data[i] / 256.0, ++n;
  return n ? sum / n : 0.0;
}

std::string envelope_text(const nlohmann::json& j, const fs::path& file) {
  const auto mm = [&](const char* key) {
    return format_number(1000 * number_at(j, std::string("/envelope/") + key, file), "%.0f");
  };
  return mm("length_m") + " × " + mm("width_m") + " × " + mm("height_m") + " mm";
}

struct PairImages {
  ColorImage left, right;
  GrayImage truth, found;
  DepthImage disparity;
};

PairImages read_pair(const fs::path& dir) {
  const fs::path pair = dir / "data" / "pair_000";
  return {io::read_color(detail::required_file(pair / "left.png", "simulate seedling")),
          io::read_color(detail::required_file(pair / "right.png", "simulate seedling")),
          io::read_gray(detail::required_file(pair / "mask.png", "simulate seedling")),
          io::read_gray(detail::required_file(dir / "mask.png", "detect seedling --mask")),
          io::read_u16(detail::required_file(dir / "disparity.png", "stereo disparity"))};
}

// The seedling is a small part of a wide view: the picture zooms on it (a 4:3 window 2.2 times
// the masks' box), left view with the outlines, right view shifted by the seedling's disparity so
// that it stands at the same place, and the disparity.
std::string picture(const fs::path& dir, const std::string& envelope) {
  PairImages p = read_pair(dir);
  draw_label_outlines(p.left, as_labels(p.truth), {255, 255, 255});
  draw_label_outlines(p.left, as_labels(p.found), {40, 230, 90});
  PixelBox b = mask_box({&p.truth, &p.found});
  if (b.empty()) b = {p.left.width / 2 - 40, p.left.height / 2 - 30, p.left.width / 2 + 40, p.left.height / 2 + 30};
  const int w = std::max({160, int(2.2 * (b.u1 - b.u0 + 1)), int(2.2 * (b.v1 - b.v0 + 1) * 4 / 3)}), h = w * 3 / 4;
  const int x = (b.u0 + b.u1 - w) / 2, y = (b.v0 + b.v1 - h) / 2;
  const int shift = int(std::lround(mean_disparity(p.disparity, p.found)));
  const int k = std::max(1, 360 / h), gap = 12;
  SvgOverlay o(side_by_side({upscale(crop(p.left, x, y, w, h), k), upscale(crop(p.right, x - shift, y, w, h), k),
                             upscale(crop(disparity_colormap(p.disparity), x, y, w, h), k)},
                            gap),
               1100);
  const double step = double(std::min(w, p.left.width) * k + gap);
  o.text(10, 28, "left: found (green), truth (white)", "white", 20);
  o.text(step + 10, 28, "right (shifted " + std::to_string(shift) + " px)", "white", 20);
  o.text(2 * step + 10, 28, "disparity (SGM): near red, far blue", "white", 20);
  o.text(10, double(o.height()) - 12, "envelope " + envelope, "#28e65a", 22);
  return o.svg();
}

}  // namespace

SystemSummary seedling_summary(const fs::path& dir) {
  const fs::path det_file = detail::required_file(dir / "detect.json", "detect seedling --out");
  const fs::path truth_file = dir / "data" / "pair_000" / "truth.json";
  const fs::path eval_file = detail::required_file(dir / "eval.json", "eval seedling --json");
  const nlohmann::json det = detail::read_json_object(det_file);
  const nlohmann::json truth = detail::read_json_object(truth_file);
  const nlohmann::json ev = detail::read_json_object(eval_file);
  SystemSummary s;
  s.picture_svg = picture(dir, envelope_text(det, det_file));
  s.caption =
      "Pair 0 of the simulated data set: the seedling the pipeline found (SGM disparity, soil plane, GMM) "
      "outlined in green, the simulator's mask in white; the right view; the disparity the "
      "pipeline measured.";
  const double ratio =
      number_at(det, "/envelope/volume_m3", det_file) / number_at(truth, "/envelope/volume_m3", truth_file);
  s.figures = {
      {"envelope L × W × H, measured (truth " + envelope_text(truth, truth_file) + ")", envelope_text(det, det_file)},
      {"envelope volume, measured / true, this pair", format_number(100 * ratio, "%.1f %%")},
      {"recognition rate / sensitivity, " + format_number(number_at(ev, "/pairs", eval_file), "%.0f") + " pairs",
       format_number(100 * number_at(ev, "/recognition_rate", eval_file), "%.0f %%") + " / " +
           format_number(100 * number_at(ev, "/sensitivity", eval_file), "%.1f %%")},
      {"per pair (SGM, plane, GMM), mean", format_number(number_at(ev, "/ms_total", eval_file), "%.0f ms")}};
  s.note =
      "Simulated stereo pairs (docs/simulator.md), not the paper's field images; the real-pair figures are "
      "in docs/pipelines/broccoli-seedlings.md.";
  s.commands = detail::section_commands(dir, {"cropsight simulate seedling --out DIR/data",
                                              "cropsight detect seedling --left DIR/data/pair_000/left.png --right "
                                              "DIR/data/pair_000/right.png --calib DIR/data/rig.yaml --out "
                                              "DIR/detect.json --mask DIR/mask.png",
                                              "cropsight eval seedling --data DIR/data --json"});
  return s;
}

}  // namespace cropsight::report
