// The potato chapter's opening: one frame of the harvest loop with the target's box, its 3D centre
// projected back into the image, its length axis, size and angle; the loop's errors against the
// simulator's truth (eval potato).
#include <cmath>
#include <cstdio>
#include <numbers>

#include "cropsight/io/image_io.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/report/demo_page.hpp"
#include "cropsight/report/svg_overlay.hpp"
#include "number_format.hpp"
#include "section_files.hpp"

namespace cropsight::report {

namespace {

namespace fs = std::filesystem;
using detail::format_number;
using detail::number_at;

// The message shown: the middle one of the frames whose target is in view with depth and angle
// and not cut by the border (a cut box's centre is the visible part's); else the middle one with
// a target; Error when no frame has one.
const nlohmann::json& shown_message(const std::vector<nlohmann::json>& messages, const fs::path& file) {
  std::vector<const nlohmann::json*> full, any;
  for (const auto& m : messages) {
    if (!m.value("detection", false) || !m.value("depth_ok", false)) continue;
    any.push_back(&m);
    if (!m.value("cut", true) && m.value("angle_ok", false)) full.push_back(&m);
  }
  const auto& pick = full.empty() ? any : full;
  if (pick.empty()) throw Error(file.string(), "no frame with a positioned target");
  return *pick[pick.size() / 2];
}

std::string picture(const fs::path& data, const nlohmann::json& m, const fs::path& file) {
  const int frame = int(number_at(m, "/frame", file));
  char name[32];
  std::snprintf(name, sizeof name, "%06d.png", frame);
  const ColorImage img = io::read_color(detail::required_file(data / "color" / name, "simulate potato"));
  const CameraIntrinsics cam = io::read_camera_yaml(data / "camera.yaml");
  const double x = number_at(m, "/x", file), y = number_at(m, "/y", file), z = number_at(m, "/z", file);
  const double u = cam.fx * x / z + cam.cx + 0.5, v = cam.fy * y / z + cam.cy + 0.5;  // pixel corners
  const double x1 = number_at(m, "/box/0", file), y1 = number_at(m, "/box/1", file);
  const double x2 = number_at(m, "/box/2", file), y2 = number_at(m, "/box/3", file);
  const double a = number_at(m, "/angle", file), half = 0.6 * std::max(x2 - x1, y2 - y1);
  SvgOverlay o(img, 760);
  o.rect(x1, y1, x2, y2, "#28e65a", 2);
  // The angle is counter-clockwise from the image x axis; image y points down.
  o.line(u - half * std::cos(a), v + half * std::sin(a), u + half * std::cos(a), v - half * std::sin(a), "#ff4d4d", 2);
  o.cross(u, v, 8, "#ffe14d", 2);
  o.text(x1, std::max(16.0, y1 - 8),
         "target: x " + format_number(1000 * x, "%.0f") + ", y " + format_number(1000 * y, "%.0f") + ", z " +
             format_number(1000 * z, "%.0f") + " mm",
         "white", 15);
  o.text(x1, std::min(double(img.height) - 6, y2 + 20), "frame " + std::to_string(frame), "white", 15);
  return o.svg();
}

std::string size_text(const nlohmann::json& m, const fs::path& file) {
  return format_number(1000 * number_at(m, "/width", file), "%.0f") + " × " +
         format_number(1000 * number_at(m, "/height", file), "%.0f") + " mm";
}

}  // namespace

SystemSummary potato_summary(const fs::path& dir) {
  const fs::path targets = dir / "targets.jsonl", eval_file = dir / "eval.json", run_file = dir / "harvest.json";
  const std::vector<nlohmann::json> messages = detail::read_json_lines(targets);
  const nlohmann::json& m = shown_message(messages, targets);
  const nlohmann::json ev = detail::read_json_object(eval_file), run = detail::read_json_object(run_file);
  SystemSummary s;
  s.picture_svg = picture(dir / "data", m, targets);
  s.caption =
      "The harvest loop's target in one frame: its box (green), its 3D centre projected into the image "
      "(yellow cross), its length axis (red).";
  const auto mae = [&](const char* axis) {
    return format_number(number_at(ev, std::string("/position/") + axis + "/mae_mm", eval_file), "%.1f");
  };
  s.figures = {
      {"3D centre x, y, z (camera frame), frame " + std::to_string(int(number_at(m, "/frame", targets))),
       format_number(1000 * number_at(m, "/x", targets), "%.0f") + ", " +
           format_number(1000 * number_at(m, "/y", targets), "%.0f") + ", " +
           format_number(1000 * number_at(m, "/z", targets), "%.0f") + " mm"},
      {"size, width × height", size_text(m, targets)},
      {"angle of the length axis (from image x, counter-clockwise)",
       format_number(number_at(m, "/angle", targets) * 180 / std::numbers::pi, "%.0f°")},
      {"centre error x / y / z, MAE over " + format_number(number_at(ev, "/frames_positioned", eval_file), "%.0f") +
           " frames in full view; " + format_number(number_at(run, "/fps", run_file), "%.0f") + " frames/s",
       mae("x") + " / " + mae("y") + " / " + mae("z") + " mm"}};
  s.note =
      "A simulated approach (D415-like camera on an arm, docs/simulator.md), scored against the simulator's "
      "truth by eval potato; the real-image figures are in docs/pipelines/potatoes.md.";
  s.commands = detail::section_commands(dir, {"cropsight simulate potato --out DIR/data",
                                              "cropsight harvest potato --data DIR/data --out DIR/targets.jsonl",
                                              "cropsight eval potato --data DIR/data --json"});
  return s;
}

}  // namespace cropsight::report
