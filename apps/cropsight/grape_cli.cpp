#include "grape_cli.hpp"

#include "cli_common.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/sequence.hpp"

namespace cropsight::cli {

nlohmann::json grape_evaluation_json(const pipeline::grape::Figures& e) {
  const auto& m = e.confusion;
  nlohmann::json j;
  j["clouds"] = e.clouds;
  j["points"] = e.points;
  j["oacc"] = json_number(m.overall_accuracy());
  j["macc"] = json_number(m.mean_accuracy());
  j["miou"] = json_number(m.mean_iou());
  j["per_class"] = nlohmann::json::array();
  for (int c = 0; c < m.num_classes(); ++c)
    j["per_class"].push_back({{"label", c},
                              {"points", m.truth_count(c)},
                              {"accuracy", json_number(m.class_accuracy(c))},
                              {"iou", json_number(m.class_iou(c))}});
  j["ms_per_cloud"] = json_number(e.ms_per_cloud());
  for (const auto& p : pipeline::grape::grape_protocols(e))
    j["protocols"][p.name] = {{"classes", p.classes}, {"miou", json_number(p.miou)}};
  return j;
}

RgbdFrame read_grape_frame(const std::string& color, const std::string& depth, const std::string& camera) {
  RgbdFrame f;
  f.camera = io::read_camera_yaml(camera);
  f.depth = io::read_u16(depth);
  f.color = io::read_color(color);
  if (f.color.width != f.depth.width || f.color.height != f.depth.height)
    throw Error(color, "colour image size differs from the depth image");
  if (f.camera.width != f.depth.width || f.camera.height != f.depth.height)
    throw Error(camera, "camera size differs from the depth image");
  return f;
}

namespace {
nlohmann::json vec3(const Eigen::Vector3f& v) { return {v.x(), v.y(), v.z()}; }
}  // namespace

nlohmann::json bunch_json(const pipeline::grape::Bunch& b, const std::string& file) {
  nlohmann::json cut = nullptr;
  if (b.cut_point)
    cut = {{"position_m", vec3(b.cut_point->position)},
           {"direction", vec3(b.cut_point->direction)},
           {"confidence", b.cut_point->confidence}};
  return {{"file", file},
          {"roi", {b.roi.x, b.roi.y, b.roi.width, b.roi.height}},
          {"points", b.cloud.size()},
          {"label_counts", pipeline::grape::label_counts(b.cloud)},
          {"cut_point", cut}};
}

}  // namespace cropsight::cli
