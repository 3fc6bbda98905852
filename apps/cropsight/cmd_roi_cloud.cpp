// cropsight roi-cloud: grape pipeline stages 1-3 on one RGB-D frame. Bunch and peduncle boxes
// (COCO-style JSON) → ROIs (Eq. 1, overlapping ROIs merged) → coloured ROI clouds (Algorithm 1)
// → KNN-PCA normals (k = 30, towards the camera) → unit-sphere normalisation. Each ROI is
// written as DIR/roi_NNN.txt in the dataset's text format (label column 0), ready for
// `segment grape`, plus DIR/rois.json with the boxes and the normalisation (centroid in metres,
// camera frame, and scale) that maps the cloud back to metres: p_m = p * scale + centroid.
//
//   cropsight roi-cloud --color C.png --depth D.png --camera camera.yaml --detections det.json
//       --out DIR [--image-id N] [--config PRESET] [--set key=value] [--json]
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/geometry/knn_normals.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/grape_text.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/pipeline/grape_roi.hpp"

namespace cropsight::cli {
namespace {
namespace fs = std::filesystem;

struct RoiCloudOptions {
  CommonOptions common;
  std::string color, depth, camera, detections, out;
  long image_id = -1;
};

void run(const RoiCloudOptions& o) {
  pipeline::GrapeRoiConfig cfg;
  apply_config(cfg, o.common.config_map(o.common.config.empty() ? "grape-roi" : ""), "--config/--set");
  const CameraIntrinsics cam = io::read_camera_yaml(o.camera);
  const DepthImage depth = io::read_u16(o.depth);
  const ColorImage color = io::read_color(o.color);
  if (color.width != depth.width || color.height != depth.height)
    throw Error(o.color, "colour image size differs from the depth image");
  if (cam.width != depth.width || cam.height != depth.height)
    throw Error(o.camera, "camera size differs from the depth image");
  const auto dets = pipeline::read_coco_detections(o.detections, o.image_id);
  const auto rois = pipeline::grape_rois(dets, depth.width, depth.height, cfg);

  // Compute everything first, then write: no partial output on a failure half-way.
  struct Out {
    Cloud cloud;
    Box2D box;
    Eigen::Vector3f centroid;
    float scale;
  };
  std::vector<Out> outs;
  for (const auto& r : rois) {
    Out out;
    out.box = r;
    out.cloud = pipeline::roi_cloud(depth, color, cam, r, cfg);
    if (out.cloud.size() < 3) continue;  // nothing measurable in this ROI
    geometry::KnnNormalsConfig ncfg;
    ncfg.k = cfg.normal_k;
    ncfg.viewpoint = Eigen::Vector3f::Zero();  // the camera centre, in the camera frame
    out.cloud.normals = geometry::knn_normals(out.cloud.points, ncfg);
    std::tie(out.centroid, out.scale) = geometry::normalize_unit_sphere(out.cloud.points);
    out.cloud.labels.assign(out.cloud.size(), 0);
    outs.push_back(std::move(out));
  }
  fs::create_directories(o.out);
  nlohmann::json list = nlohmann::json::array();
  for (std::size_t i = 0; i < outs.size(); ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "roi_%03zu.txt", i);
    io::write_grape_text(fs::path(o.out) / name, outs[i].cloud);
    const auto& b = outs[i].box;
    list.push_back({{"file", name},
                    {"box", {b.x, b.y, b.width, b.height}},
                    {"points", outs[i].cloud.size()},
                    {"centroid_m", {outs[i].centroid.x(), outs[i].centroid.y(), outs[i].centroid.z()}},
                    {"scale_m", outs[i].scale}});
  }
  nlohmann::json j = {{"detections", dets.size()}, {"rois", list}};
  io::write_file_atomic(fs::path(o.out) / "rois.json", j.dump(2) + "\n");
  if (o.common.json)
    print_json(j);
  else
    std::printf("%zu detections -> %zu ROI clouds in %s\n", dets.size(), outs.size(), o.out.c_str());
}
}  // namespace

void add_roi_cloud(CLI::App& app) {
  auto o = std::make_shared<RoiCloudOptions>();
  auto* cmd = app.add_subcommand("roi-cloud", "Grape ROIs (Eq. 1) to coloured, normal-annotated ROI clouds");
  cmd->add_option("--color", o->color, "Colour image (registered to depth)")->required();
  cmd->add_option("--depth", o->depth, "16-bit depth image")->required();
  cmd->add_option("--camera", o->camera, "camera.yaml (intrinsics, depth_scale)")->required();
  cmd->add_option("--detections", o->detections, "COCO-style detections (bunch = 1, peduncle = 2)")->required();
  cmd->add_option("--out", o->out, "Output folder")->required();
  cmd->add_option("--image-id", o->image_id, "Keep only this COCO image_id's detections");
  add_json_flag(cmd, o->common);
  add_config_options(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
