// The grape chapter's opening: the segmented cloud seen from the camera and from the side, the
// simulator's labels beside it, the cut point the segmenter's labels give (and the true one);
// OAcc and IoU against the simulator's labels (eval::ConfusionMatrix, as eval grape counts them).
#include <array>
#include <cmath>
#include <optional>

#include "cropsight/eval/segmentation_metrics.hpp"
#include "cropsight/io/grape_text.hpp"
#include "cropsight/pipeline/grape/pipeline.hpp"
#include "cropsight/report/cloud_view.hpp"
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

// The dataset's labels, in the colours of the picture's legend.
struct LabelStyle {
  const char* name;
  Rgb8 rgb;
  const char* css;
};
constexpr std::array<LabelStyle, 6> kLabels = {{{"no return", {90, 90, 90}, "#5a5a5a"},
                                                {"berries", {123, 63, 160}, "#b07fd6"},
                                                {"peduncle", {243, 156, 18}, "#f39c12"},
                                                {"leaf", {60, 176, 67}, "#3cb043"},
                                                {"backdrop", {185, 185, 185}, "#d0d0d0"},
                                                {"noise", {231, 76, 60}, "#ff6b5a"}}};

// The simulator's normalisation (truth.json): a written point back to metres, camera frame.
struct ToCamera {
  Eigen::Matrix3f rotation = Eigen::Matrix3f::Identity();
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();
  float scale = 1;
  Eigen::Vector3f operator()(const Eigen::Vector3f& p) const { return rotation * (p * scale + centroid); }
};

ToCamera to_camera_of(const nlohmann::json& t, const fs::path& file) {
  ToCamera m;
  for (int r = 0; r < 3; ++r) {
    m.centroid[r] = float(number_at(t, "/centroid_m/" + std::to_string(r), file));
    for (int c = 0; c < 3; ++c)
      m.rotation(r, c) =
          float(number_at(t, "/to_camera_rotation/" + std::to_string(r) + "/" + std::to_string(c), file));
  }
  m.scale = float(number_at(t, "/scale_m", file));
  return m;
}

std::vector<Rgb8> colors_of(const std::vector<int>& labels) {
  std::vector<Rgb8> c;
  c.reserve(labels.size());
  for (int l : labels) c.push_back(l >= 0 && l < 6 ? kLabels[std::size_t(l)].rgb : Rgb8{0, 0, 0});
  return c;
}

// Front (from the camera: x right, y up in the dataset frame) and side (from +x) views framing the
// true bunch, peduncle and leaves; the predicted labels in both, the true labels in front.
std::string picture(const Cloud& truth, const std::vector<int>& predicted, const ToCamera& to_cam,
                    const std::optional<pipeline::grape::CutPoint>& cut, const Eigen::Vector3f& true_cut_m) {
  std::vector<Eigen::Vector3f> framed;
  for (std::size_t k = 0; k < truth.size(); ++k)
    if (truth.labels[k] >= 1 && truth.labels[k] <= 3) framed.push_back(truth.points[k]);
  const CloudView front = fit_cloud_view(framed, Eigen::Vector3f::UnitX(), Eigen::Vector3f::UnitY(), 330);
  CloudView side = fit_cloud_view(framed, -Eigen::Vector3f::UnitZ(), Eigen::Vector3f::UnitY(), 330);
  const int gap = 12;
  const ColorImage image = side_by_side(
      {render_cloud(truth, colors_of(predicted), front, 3), render_cloud(truth, colors_of(predicted), side, 3),
       render_cloud(truth, colors_of(truth.labels), front, 3)},
      gap);
  SvgOverlay o(image, 1050);
  const Eigen::Matrix3f from_cam = to_cam.rotation.transpose();
  const auto unit = [&](const Eigen::Vector3f& m) {
    return Eigen::Vector3f((from_cam * m - to_cam.centroid) / to_cam.scale);
  };
  const std::array<std::pair<const CloudView*, double>, 3> panels = {
      {{&front, 0.0}, {&side, double(front.width + gap)}, {&front, double(front.width + side.width + 2 * gap)}}};
  for (const auto& [view, offset] : panels) {
    const Eigen::Vector2f t = view->pixel(unit(true_cut_m));
    o.circle(offset + t.x(), t.y(), 9, "#00e5ff", 2);
    if (!cut) continue;
    const Eigen::Vector2f p = view->pixel(unit(cut->position));
    o.cross(offset + p.x(), p.y(), 10, "black", 3);
  }
  o.text(8, 22, "segmented, from the camera", "white", 16);
  o.text(front.width + gap + 8, 22, "segmented, from the side", "white", 16);
  o.text(front.width + side.width + 2 * gap + 8, 22, "simulator's labels", "white", 16);
  for (std::size_t l = 0; l < kLabels.size(); ++l)
    o.text(8 + 100.0 * double(l), image.height - 10.0, kLabels[l].name, kLabels[l].css, 15);
  return o.svg();
}

std::string mm_text(const Eigen::Vector3f& p) {
  return format_number(1000 * p.x(), "%.0f") + ", " + format_number(1000 * p.y(), "%.0f") + ", " +
         format_number(1000 * p.z(), "%.0f") + " mm";
}

}  // namespace

SystemSummary grape_summary(const fs::path& dir) {
  const fs::path truth_file = dir / "data" / "truth.json";
  const nlohmann::json t = detail::read_json_object(truth_file);
  const Cloud truth = io::read_grape_text(detail::required_file(dir / "data" / "cloud.txt", "simulate grape"));
  Cloud labelled = io::read_grape_text(detail::required_file(dir / "labelled.txt", "segment grape --out"));
  if (labelled.size() != truth.size())
    throw Error((dir / "labelled.txt").string(),
                "has " + std::to_string(labelled.size()) + " points, data/cloud.txt " + std::to_string(truth.size()));
  const nlohmann::json seg = detail::read_json_object(dir / "segment.json");
  eval::ConfusionMatrix cm(6);
  cm.add(truth.labels, labelled.labels);
  // The cut point as the camera pipeline computes it: on the segmented cloud in metres.
  const ToCamera to_cam = to_camera_of(t, truth_file);
  for (auto& p : labelled.points) p = to_cam(p);
  const std::optional<pipeline::grape::CutPoint> cut = pipeline::grape::grape_cut_point(labelled);
  Eigen::Vector3f true_cut;
  for (int r = 0; r < 3; ++r)
    true_cut[r] = float(number_at(t, "/cut_point/position_m/" + std::to_string(r), truth_file));

  SystemSummary s;
  s.picture_svg = picture(truth, labelled.labels, to_cam, cut, true_cut);
  s.caption =
      "The simulated bunch's cloud labelled by the shipped grape-best segmenter, seen from the camera and "
      "from the side, and the simulator's own labels. Cyan ring: the true cut point (centroid of the visible "
      "peduncle); black cross: the cut point from the segmenter's labels, when it finds one.";
  s.figures = {
      {"OAcc / mIoU (six labels), this cloud",
       format_number(cm.overall_accuracy(), "%.3f") + " / " + format_number(cm.mean_iou(), "%.3f")},
      {"IoU berries / peduncle / leaf", format_number(cm.class_iou(1), "%.2f") + " / " +
                                            format_number(cm.class_iou(2), "%.2f") + " / " +
                                            format_number(cm.class_iou(3), "%.2f")},
      {cut ? "cut point (camera frame), " + format_number(1000 * (cut->position - true_cut).norm(), "%.0f") +
                 " mm from the true one"
           : "cut point: the segmenter labelled no peduncle cluster of 10 points (true: " + mm_text(true_cut) + ")",
       cut ? mm_text(cut->position) : "none"},
      {"segmentation, " + format_number(double(truth.size()), "%.0f") + " points",
       format_number(number_at(seg, "/ms", dir / "segment.json"), "%.0f ms")}};
  s.note =
      "Scored on a simulated cloud (simulate grape), not on the real data: it says how close the simulator "
      "comes to the clouds the models were trained on as much as how good the segmenter is. On the real "
      "clouds the shipped ensemble scores OAcc 0.968, mIoU 0.854 (4-fold, held out) and peduncle IoU 0.48 "
      "(held-out fold 1; docs/pipelines/grape-bunches.md).";
  s.commands = detail::section_commands(dir, {"cropsight simulate grape --out DIR/data",
                                              "cropsight segment grape --config grape-best --clouds DIR/data/cloud.txt "
                                              "--out DIR/labelled.txt --json"});
  return s;
}

}  // namespace cropsight::report
