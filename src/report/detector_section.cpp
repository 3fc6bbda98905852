// The 2D detector's chapter opening: the first image with the boxes `detect objects` found
// (scores at least kDetectorShownScore), the true boxes dashed when the folder has labels, and
// how many true objects a shown box covers at IoU >= 0.5 (eval::voc_iou).
#include <algorithm>
#include <map>

#include "cropsight/eval/voc_ap.hpp"
#include "cropsight/io/file_names.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/report/demo_page.hpp"
#include "cropsight/report/svg_overlay.hpp"
#include "number_format.hpp"
#include "section_files.hpp"

namespace cropsight::report {

namespace {

namespace fs = std::filesystem;
using detail::format_number;
using detail::number_at;

// Truth boxes (inclusive pixel corners) of the instances in a 16-bit label image, those of at
// least 100 pixels: a sliver at the border or behind a root is no object to find.
std::vector<eval::VocBox> truth_boxes(const LabelImage& labels) {
  std::map<int, eval::VocBox> box;
  std::map<int, int> count;
  for (int v = 0; v < labels.height; ++v)
    for (int u = 0; u < labels.width; ++u) {
      const int id = labels.at(u, v);
      if (id == 0) continue;
      auto [it, fresh] = box.try_emplace(id, eval::VocBox{double(u), double(v), double(u), double(v)});
      eval::VocBox& b = it->second;
      b.x1 = std::min(b.x1, double(u)), b.y1 = std::min(b.y1, double(v));
      b.x2 = std::max(b.x2, double(u)), b.y2 = std::max(b.y2, double(v));
      ++count[id];
    }
  std::vector<eval::VocBox> out;
  for (const auto& [id, b] : box)
    if (count[id] >= 100) out.push_back(b);
  return out;
}

// The shown boxes of one image from detections.json (COCO results: bbox = x, y, w, h).
std::vector<eval::VocBox> shown_boxes(const nlohmann::json& dets, const std::string& file_name, int& all) {
  std::vector<eval::VocBox> out;
  all = 0;
  for (const auto& d : dets) {
    if (d.value("file_name", "") != file_name) continue;
    ++all;
    const auto& b = d.at("bbox");
    const double score = d.value("score", 0.0);
    if (score < kDetectorShownScore) continue;
    const double x = b.at(0), y = b.at(1), w = b.at(2), h = b.at(3);
    out.push_back({x, y, x + w, y + h, score});
  }
  return out;
}

int covered(const std::vector<eval::VocBox>& truth, const std::vector<eval::VocBox>& found) {
  return int(std::count_if(truth.begin(), truth.end(), [&](const eval::VocBox& t) {
    return std::any_of(found.begin(), found.end(), [&](const eval::VocBox& f) { return eval::voc_iou(t, f) >= 0.5; });
  }));
}

}  // namespace

SystemSummary detector_summary(const fs::path& dir) {
  const std::vector<fs::path> images = io::list_images(dir / "images");
  if (images.empty()) throw Error((dir / "images").string(), "no image");
  const fs::path dets_file = dir / "objects" / "detections.json", run_file = dir / "detect.json";
  const nlohmann::json dets = detail::read_json_file(dets_file), run = detail::read_json_object(run_file);
  if (!dets.is_array()) throw Error(dets_file.string(), "expected a JSON array of detections");
  const fs::path& shown = images.front();
  int all = 0;
  const std::vector<eval::VocBox> found = shown_boxes(dets, shown.filename().string(), all);
  const fs::path label_file = dir / "labels" / shown.filename();
  const std::vector<eval::VocBox> truth =
      fs::is_regular_file(label_file) ? truth_boxes(io::read_u16(label_file)) : std::vector<eval::VocBox>{};

  SvgOverlay o(io::read_color(shown), 760);
  for (const auto& t : truth) o.rect(t.x1, t.y1, t.x2 + 1, t.y2 + 1, "white", 2, true);
  for (const auto& f : found) {
    o.rect(f.x1, f.y1, f.x2, f.y2, "#28e65a", 2);
    o.text(f.x1, std::max(14.0, f.y1 - 5), format_number(f.score, "%.2f"), "#28e65a", 14);
  }
  SystemSummary s;
  s.picture_svg = o.svg();
  s.caption = "Boxes of the project's CenterNet (models/potato-cnn.onnx through OpenCV DNN) scoring at least " +
              format_number(kDetectorShownScore, "%.1f") + " (green, with the score)" +
              (truth.empty() ? "." : "; the simulator's potatoes dashed white.");
  s.figures = {{"boxes shown (score ≥ " + format_number(kDetectorShownScore, "%.1f") + "), of all boxes on " +
                    shown.filename().string(),
                std::to_string(found.size()) + " of " + std::to_string(all)},
               {"per image, " + format_number(number_at(run, "/images", run_file), "%.0f") + " images",
                format_number(number_at(run, "/ms_per_image", run_file), "%.0f ms")}};
  if (!truth.empty())
    s.figures.insert(s.figures.begin() + 1,
                     {"true potatoes (≥ 100 px) covered by a shown box at IoU ≥ 0.5",
                      std::to_string(covered(truth, found)) + " of " + std::to_string(truth.size())});
  s.note =
      "The detector was trained on the shared real potato images (docs/pipelines/detector.md); these frames are "
      "simulated, so its boxes on roots and strings show the gap between the two, not its accuracy on real "
      "images.";
  s.commands = detail::section_commands(
      dir, {"cropsight detect objects --model models/potato-cnn.onnx --images DIR/images --out DIR/objects --json"});
  return s;
}

}  // namespace cropsight::report
