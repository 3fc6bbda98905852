// cropsight detect grape: the grape pipeline from the camera on one RGB-D frame
// (pipeline::grape::Pipeline): bunch and peduncle boxes (the project's detector, or a COCO file)
// → ROIs (Eq. 1, overlapping ones merged) → coloured ROI clouds → normals → the grape segmenter →
// per bunch a labelled cloud in metres (camera frame) and a cut point on its peduncle.
//
//   cropsight detect grape --color C.png --depth D.png --camera camera.yaml
//       (--detector DET.onnx|DET.pt | --detections COCO.json [--image-id N])
//       [--segmenter PRESET|MODEL] --out DIR [--config PRESET] [--set key=value] [--json]
//
// DIR gets bunch_NNN.ply (points in metres with colour, normal and label) and cut_points.json
// (per bunch: its file, ROI, label counts and cut point, null when the bunch shows no peduncle
// cluster of cut_point.min_points points); --overlay a picture of it all. DIR is replaced whole (a temporary sibling
// renamed), so it never mixes two runs' files; an existing DIR must be empty or a previous run's output.
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/core/threads.hpp"
#include "cropsight/io/cloud_io.hpp"
#include "cropsight/io/config_yaml.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/pipeline/grape/make_pipeline.hpp"
#include "cropsight/pipeline/grape/pipeline.hpp"
#include "cropsight/pipeline/grape/truth.hpp"
#include "cropsight/report/frame_overlays.hpp"
#include "grape_cli.hpp"
#include "grape_segmenter_options.hpp"

namespace cropsight::cli {
namespace detect_grape_cmd {
namespace fs = std::filesystem;

struct DetectGrapeOptions {
  CommonOptions common;
  std::string color, depth, camera, detector, detections, out, overlay;
  long image_id = -1;
  int threads = 2;
  bool force = false;
  GrapeSegmenterOptions segmenter;
};

void run(const DetectGrapeOptions& o) {
  check_thread_count(o.threads, "--threads");
  // Before any model loads: a bad --out costs nothing and names the folder.
  io::OutputPolicy policy = output_policy(
      "detect grape", o.force,
      {o.color, o.depth, o.camera, o.detector, o.detections, o.segmenter.config().model, o.common.config});
  io::OutputFolder out(o.out, policy);
  policy.inputs.emplace_back(o.out);  // the two outputs must not overlap
  std::optional<io::OutputFolder> overlay;
  if (!o.overlay.empty()) overlay.emplace(o.overlay, policy);
  pipeline::PipelineSpec spec{o.common.config, o.common.sets, "", o.detector, o.threads};
  o.segmenter.add_to_spec(spec);
  const auto built = pipeline::grape::make_pipeline(spec);
  pipeline::grape::Pipeline& pipe = *built;
  const pipeline::grape::SegmenterConfig& scfg = pipe.segmenter().config();
  const RgbdFrame frame = read_grape_frame(o.color, o.depth, o.camera);
  std::vector<pipeline::grape::Detection> given;
  if (!o.detections.empty()) given = pipeline::grape::read_coco_detections(o.detections, o.image_id);

  // Everything is computed before anything is written: no partial output on a failure.
  const pipeline::grape::FrameResult r = o.detections.empty() ? pipe.process(frame) : pipe.process(frame, given);
  const std::string source = o.detections.empty() ? o.detector : o.detections;
  for (const auto& d : r.outside) {
    const Box2D& b = d.box;
    std::fprintf(stderr,
                 "cropsight: warning: %s: detection %ld: box [%d, %d, %d, %d] lies outside the %dx%d image; skipped\n",
                 source.c_str(), d.annotation, b.x, b.y, b.width, b.height, frame.depth.width, frame.depth.height);
  }
  nlohmann::json bunches = nlohmann::json::array();
  for (std::size_t i = 0; i < r.bunches.size(); ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "bunch_%03zu.ply", i);
    bunches.push_back(bunch_json(r.bunches[i], name));
  }
  nlohmann::json j = {{"color", o.color},
                      {"depth", o.depth},
                      {"boxes_from", o.detections.empty() ? "detector" : "detections"},
                      {"boxes_file", source},
                      {"detections", r.detections.size()},
                      {"outside_image", r.outside.size()},
                      {"segmenter", scfg.model},
                      {"bunches", bunches}};
  GrapeSegmenterOptions::describe(scfg, j);  // votes, and the ensemble partner when there is one
  for (std::size_t i = 0; i < r.bunches.size(); ++i)
    io::write_cloud(out.path() / bunches[i]["file"].get<std::string>(), r.bunches[i].cloud);
  io::write_file_atomic(out.path() / "cut_points.json", j.dump(2) + "\n");
  if (overlay)
    io::write_color(overlay->path() / (fs::path(o.color).stem().string() + ".png"),
                    report::grape_frame_overlay(frame.color, frame.camera, r));
  out.commit("grape bunches");
  if (overlay) overlay->commit("overlay folder");
  if (o.common.json) {
    j["out"] = o.out;
    j["ms"] = json_number(r.timer.total_ms());
    print_json(j);
  } else {
    std::printf("%zu detections -> %zu bunches (%zu with a cut point) in %.0f ms -> %s\n", r.detections.size(),
                r.bunches.size(), r.cut_points(), r.timer.total_ms(), o.out.c_str());
  }
}
}  // namespace detect_grape_cmd

void add_detect_grape(CLI::App& detect) {
  using namespace detect_grape_cmd;
  auto o = std::make_shared<DetectGrapeOptions>();
  auto* cmd = detect.add_subcommand(
      "grape", "Grape bunches from one RGB-D frame: boxes, ROI cloud, segmentation, a cut point per bunch");
  cmd->add_option("--color", o->color, "Colour image (8-bit, registered to depth)")->required();
  cmd->add_option("--depth", o->depth, "16-bit depth image")->required();
  cmd->add_option("--camera", o->camera, "camera.yaml (intrinsics, depth_scale) of the depth image")->required();
  auto* det =
      cmd->add_option("--detector", o->detector,
                      "The project's grape detector (classes grape and peduncle): a name such as detector-grape "
                      "(its .pt under libtorch where the plugin is built, else its .onnx: "
                      "detector.backend) or a .pt / .onnx file");
  auto* dets = cmd->add_option("--detections", o->detections,
                               "Boxes instead of a detector: COCO-style JSON (bunch = 1, peduncle = 2; an "
                               "\"annotations\" file or a results array)");
  det->excludes(dets);
  dets->excludes(det);
  cmd->add_option("--image-id", o->image_id, "With --detections: keep only this COCO image_id's boxes")->needs(dets);
  cmd->add_option("--out", o->out, "New output folder: bunch_NNN.ply (labelled, metres, camera frame), cut_points.json")
      ->required();
  cmd->add_option("--overlay", o->overlay,
                  "New folder for a picture: bunch points by label, boxes, ROIs, cut points (<colour stem>.png)");
  add_force_flag(cmd, o->force);
  cmd->add_option("--threads", o->threads,
                  "Threads of the segmenter and the .pt detector, 1.." + std::to_string(kMaxThreads) + " (default 2)");
  o->segmenter.add_options(cmd, "grape-best", "--segmenter");
  add_json_flag(cmd, o->common);
  cmd->add_option("--config", o->common.config,
                  "Pipeline preset (configs/<name>.yaml or a YAML file; default grape-camera): roi.*, cut_point.*");
  cmd->add_option("--set", o->common.sets, "Override a pipeline parameter: key=value (repeatable)")->take_all();
  cmd->callback([o] {
    if (o->detector.empty() && o->detections.empty())
      throw Error("detect grape", "give --detector (a model) or --detections (a COCO file) for the boxes");
    run(*o);
  });
}

}  // namespace cropsight::cli
