// cropsight detect potato (issue 22): every image of a folder -> <stem>.txt in the paper's format
// ("potato score x1 y1 x2 y2"), optional overlays with the boxes, one JSON line per image. The
// detection is the library's Detector2D; this file parses options and writes the outputs, each
// output folder whole or not at all (temporary folder, then rename).
#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/voc.hpp"
#include "cropsight/pipeline/potato/potato_overlay.hpp"
#include "potato_cli.hpp"

namespace cropsight::cli {
namespace {
namespace fs = std::filesystem;

struct Options {
  CommonOptions common;
  std::string images, out, overlay;
};

std::vector<fs::path> list_images(const fs::path& dir) {
  if (!fs::is_directory(dir)) throw Error(dir.string(), "not a folder of images");
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    std::string ext = e.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (e.is_regular_file() && (ext == ".jpg" || ext == ".jpeg" || ext == ".png")) out.push_back(e.path());
  }
  if (out.empty()) throw Error(dir.string(), "holds no .jpg or .png image");
  std::sort(out.begin(), out.end());
  return out;
}

void run(const Options& o) {
  auto detector = potato_detector(o.common);  // a bad key fails before any image is read
  const std::vector<std::string> names = detector->class_names();
  const auto files = list_images(o.images);
  io::TempDirectory out(o.out);
  std::unique_ptr<io::TempDirectory> overlay;
  if (!o.overlay.empty()) overlay = std::make_unique<io::TempDirectory>(o.overlay);
  for (const fs::path& f : files) {
    ColorImage img = io::read_color(f);
    Stopwatch sw;
    const std::vector<Detection2D> dets = detector->detect({&img, nullptr});
    const double ms = sw.ms();
    const std::string stem = f.stem().string();
    io::write_detection_text(out.path() / (stem + ".txt"), dets, names);
    if (overlay) {
      pipeline::potato::draw_detections(img, dets);
      io::write_color(overlay->path() / (stem + ".png"), img);
    }
    if (o.common.json) {
      nlohmann::json boxes = nlohmann::json::array();
      for (const Detection2D& d : dets)
        boxes.push_back({{"class", names[std::size_t(d.class_id)]},
                         {"score", d.score},
                         {"x1", d.x1},
                         {"y1", d.y1},
                         {"x2", d.x2},
                         {"y2", d.y2}});
      print_json({{"image", f.filename().string()}, {"detections", boxes}, {"ms", ms}});
    } else {
      std::printf("%s: %zu potato%s (%.2f ms)\n", f.filename().string().c_str(), dets.size(),
                  dets.size() == 1 ? "" : "es", ms);
    }
  }
  out.commit("detection folder");
  if (overlay) overlay->commit("overlay folder");
}

}  // namespace

void add_detect_potato(CLI::App& detect) {
  auto o = std::make_shared<Options>();
  auto* cmd = detect.add_subcommand("potato", "Detect potatoes in a folder of images (issue 22)");
  cmd->add_option("--images", o->images, "Folder of .jpg/.png images")->required();
  cmd->add_option("--out", o->out, "Folder to write <stem>.txt detections into (replaced whole)")->required();
  cmd->add_option("--overlay", o->overlay, "Folder to write <stem>.png images with the boxes into");
  add_json_flag(cmd, o->common);
  add_config_options(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
