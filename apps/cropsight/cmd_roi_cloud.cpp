// cropsight roi-cloud: grape pipeline stages 1-3 on one RGB-D frame (pipeline::grape::grape_roi_clouds).
// Bunch and peduncle boxes (COCO-style JSON) → ROIs (Eq. 1, overlapping ROIs merged) → coloured
// ROI clouds (Algorithm 1) → KNN-PCA normals (k = 30, towards the camera) → unit-sphere
// normalisation. Each ROI is
// written as DIR/roi_NNN.txt in the dataset's text format (label column 0), ready for
// `segment grape`, plus DIR/rois.json with the boxes and the normalisation (centroid in metres,
// camera frame, and scale) that maps the cloud back to metres: p_m = p * scale + centroid.
//
//   cropsight roi-cloud --color C.png --depth D.png --camera camera.yaml --detections det.json
//       --out DIR [--image-id N] [--config PRESET] [--set key=value] [--json]
//
// DIR is replaced as a whole: the new set is written into a temporary sibling folder and swapped
// in, so a second run never leaves the first run's roi_NNN.txt next to a rois.json that does not
// list them. To protect other files, an existing DIR must be empty or a previous run's output.
// Detections whose box lies wholly outside the image are skipped with a warning line.

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/grape_text.hpp"
#include "cropsight/pipeline/grape/roi.hpp"
#include "grape_cli.hpp"

namespace cropsight::cli {
namespace roi_cloud_cmd {
namespace fs = std::filesystem;

struct RoiCloudOptions {
  CommonOptions common;
  std::string color, depth, camera, detections, out;
  long image_id = -1;
  bool force = false;
};

void run(const RoiCloudOptions& o) {
  // The set goes into a temporary sibling of the folder, then replaces it: the folder holds the
  // previous run's files or all of this run's, never a mix; the temporary goes on any failure.
  io::OutputFolder out(
      o.out, output_policy("roi-cloud", o.force, {o.color, o.depth, o.camera, o.detections, o.common.config}));
  pipeline::grape::RoiConfig cfg;
  apply_config(cfg, o.common.config_map(o.common.config.empty() ? "grape-roi" : ""), "--config/--set");
  cfg.validate("--config/--set");
  const RgbdFrame f = read_grape_frame(o.color, o.depth, o.camera);
  const CameraIntrinsics& cam = f.camera;
  const DepthImage& depth = f.depth;
  const ColorImage& color = f.color;
  const auto dets = pipeline::grape::read_coco_detections(o.detections, o.image_id);
  // Compute everything first (the library's stages 1-3), then write: no partial output on a
  // failure half-way.
  const pipeline::grape::RoiFrame frame = pipeline::grape::grape_roi_clouds(depth, color, cam, dets, cfg);
  for (const auto& d : frame.outside) {
    const Box2D& b = d.box;
    std::fprintf(stderr,
                 "cropsight: warning: %s: annotation %ld: bbox [%d, %d, %d, %d] lies outside the %dx%d image; "
                 "skipped\n",
                 o.detections.c_str(), d.annotation, b.x, b.y, b.width, b.height, depth.width, depth.height);
  }
  const auto& outs = frame.rois;
  nlohmann::json list = nlohmann::json::array();
  for (std::size_t i = 0; i < outs.size(); ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "roi_%03zu.txt", i);
    const auto& b = outs[i].box;
    list.push_back({{"file", name},
                    {"box", {b.x, b.y, b.width, b.height}},
                    {"points", outs[i].cloud.size()},
                    {"centroid_m", {outs[i].centroid.x(), outs[i].centroid.y(), outs[i].centroid.z()}},
                    {"scale_m", outs[i].scale}});
  }
  nlohmann::json j = {{"detections", dets.size()}, {"outside_image", frame.outside.size()}, {"rois", list}};
  for (std::size_t i = 0; i < outs.size(); ++i)
    io::write_grape_text(out.path() / list[i]["file"].get<std::string>(), outs[i].cloud);
  io::write_file_atomic(out.path() / "rois.json", j.dump(2) + "\n");
  out.commit("ROI clouds");
  if (o.common.json)
    print_json(j);
  else
    std::printf("%zu detections -> %zu ROI clouds in %s\n", dets.size(), outs.size(), o.out.c_str());
}
}  // namespace roi_cloud_cmd

void add_roi_cloud(CLI::App& app) {
  using namespace roi_cloud_cmd;
  auto o = std::make_shared<RoiCloudOptions>();
  auto* cmd = app.add_subcommand("roi-cloud", "Grape ROIs (Eq. 1) to coloured, normal-annotated ROI clouds");
  cmd->add_option("--color", o->color, "Colour image (registered to depth)")->required();
  cmd->add_option("--depth", o->depth, "16-bit depth image")->required();
  cmd->add_option("--camera", o->camera, "camera.yaml (intrinsics, depth_scale)")->required();
  cmd->add_option("--detections", o->detections, "COCO-style detections (bunch = 1, peduncle = 2)")->required();
  cmd->add_option("--out", o->out, "New output folder (roi_NNN.txt clouds, rois.json)")->required();
  add_force_flag(cmd, o->force);
  cmd->add_option("--image-id", o->image_id, "Keep only this COCO image_id's detections");
  add_json_flag(cmd, o->common);
  add_config_options(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
