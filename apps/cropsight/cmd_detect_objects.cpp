// cropsight detect objects --model det.pt|det.onnx --images DIR --out DIR [--threshold S] [--json]:
// runs the project's detector on every image of DIR (sorted; .jpg, .jpeg, .png) and writes
// OUT/<stem>.txt per image (the paper's text format, "class score x1 y1 x2 y2") and
// OUT/detections.json (COCO results: file_name, image_id = index in the sorted list or, with --coco,
// the COCO file's id of the image, category_id = class index + 1, bbox [x, y, w, h], score);
// --overlay a picture per image.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/config_yaml.hpp"
#include "cropsight/io/file_names.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/voc.hpp"
#include "cropsight/nn/center_onnx.hpp"
#include "cropsight/nn/detection_dataset.hpp"
#include "cropsight/report/frame_overlays.hpp"

namespace cropsight::cli {

namespace detect_objects_cmd {
using io::list_images;
}  // namespace detect_objects_cmd

void add_detect_objects(CLI::App& detect) {
  using namespace detect_objects_cmd;
  struct Options {
    std::string model, images, out, overlay, coco;
    int threads = 1;
    bool force = false;
    CommonOptions common;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = detect.add_subcommand("objects", "Run the project's 2D detector (.pt or .onnx) on a folder of images");
  cmd->add_option("--model", o->model, "Detector: .pt (libtorch) or .onnx (OpenCV DNN)")->required();
  cmd->add_option("--images", o->images, "Folder of images")->required();
  cmd->add_option("--out", o->out, "New output folder (per-image .txt and detections.json)")->required();
  cmd->add_option("--overlay", o->overlay, "New folder for pictures with the boxes, classes and scores (<stem>.png)");
  cmd->add_option("--coco", o->coco, "COCO file of these images: detections.json takes its image ids");
  add_force_flag(cmd, o->force);
  cmd->add_option("--threads", o->threads, "libtorch threads (.pt)")->check(CLI::Range(1, 256));
  add_json_flag(cmd, o->common);
  cmd->callback([o] {
    // Written whole or not at all: a bad image half-way leaves no folder of partial results.
    io::OutputPolicy policy = output_policy("detect objects", o->force, {o->images, o->model});
    io::OutputFolder out(o->out, policy);
    policy.inputs.emplace_back(o->out);
    std::optional<io::OutputFolder> overlay;
    if (!o->overlay.empty()) overlay.emplace(o->overlay, policy);
    const auto files = list_images(o->images);
    // With --coco, results carry the annotations' image ids, so COCO tools score them as they are.
    std::vector<long> ids(files.size());
    const auto known = o->coco.empty() ? std::map<std::string, long>{} : nn::coco_image_ids(o->coco);
    for (std::size_t i = 0; i < files.size(); ++i) {
      const auto it = known.find(files[i].filename().string());
      if (!o->coco.empty() && it == known.end())
        throw Error(files[i].string(), "is not among the images of " + o->coco);
      ids[i] = o->coco.empty() ? long(i) : it->second;
    }
    auto det = nn::load_center_detector(io::find_model(o->model).string(), o->threads);
    const auto names = det->class_names();
    nlohmann::json results = nlohmann::json::array();
    std::size_t boxes = 0;
    const Stopwatch clock;
    for (std::size_t i = 0; i < files.size(); ++i) {
      const ColorImage im = io::read_color(files[i]);
      const auto d = det->detect({&im, nullptr});
      io::write_detection_text(out.path() / (files[i].stem().string() + ".txt"), d, names);
      if (overlay)
        io::write_color(overlay->path() / (files[i].stem().string() + ".png"), report::detection_overlay(im, d, names));
      for (const auto& b : d)
        results.push_back({{"file_name", files[i].filename().string()},
                           {"image_id", ids[i]},
                           {"category_id", b.class_id + 1},
                           {"bbox", {b.x1, b.y1, b.width(), b.height()}},
                           {"score", b.score}});
      boxes += d.size();
    }
    const double seconds = clock.seconds();
    io::write_atomic_with(out.path() / "detections.json",
                          [&](const std::filesystem::path& tmp) { std::ofstream(tmp) << results.dump() << "\n"; });
    out.commit("detections");
    if (overlay) overlay->commit("overlay folder");
    if (o->common.json)
      print_json({{"images", files.size()},
                  {"boxes", boxes},
                  {"out", o->out},
                  {"ms_per_image", json_number(1000 * seconds / double(files.size()))}});
    else
      std::printf("%zu images, %zu boxes -> %s\n", files.size(), boxes, o->out.c_str());
  });
}

}  // namespace cropsight::cli
