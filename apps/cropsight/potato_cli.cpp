#include "potato_cli.hpp"

namespace cropsight::cli {

namespace {
std::string preset_of(const CommonOptions& common) { return common.config.empty() ? "potato" : common.config; }
}  // namespace

pipeline::potato::Config potato_config(const CommonOptions& common) {
  return pipeline::potato::spec_config({common.config, common.sets});
}

std::unique_ptr<pipeline::potato::Pipeline> make_potato(const CommonOptions& common, const std::string& model) {
  return pipeline::potato::make_pipeline({common.config, common.sets, model});
}

std::unique_ptr<Detector2D> potato_detector(const CommonOptions& common) {
  return pipeline::potato::make_detector(potato_config(common).detector, preset_of(common));
}

nlohmann::json harvest_json(const pipeline::potato::HarvestTarget& t) {
  nlohmann::json j{{"frame", t.frame},
                   {"timestamp", json_number(t.timestamp)},
                   {"detection", t.detection},
                   {"depth_ok", t.depth_ok},
                   {"x", json_number(t.x)},
                   {"y", json_number(t.y)},
                   {"z", json_number(t.z)},
                   {"height", json_number(t.height)},
                   {"width", json_number(t.width)},
                   {"angle", json_number(t.angle)},
                   {"angle_ok", t.angle_ok},
                   {"cut", t.cut},
                   {"target_id", t.target_id},
                   {"state", config_name(t.state)},
                   {"score", json_number(t.score)}};
  if (t.detection)
    j["box"] = {json_number(t.box.x1), json_number(t.box.y1), json_number(t.box.x2), json_number(t.box.y2)};
  return j;
}

nlohmann::json detections_json(const std::vector<Detection2D>& dets, const std::vector<std::string>& names,
                               const std::vector<std::optional<double>>& angles) {
  nlohmann::json boxes = nlohmann::json::array();
  for (std::size_t i = 0; i < dets.size(); ++i) {
    const Detection2D& d = dets[i];
    nlohmann::json b{{"class", names[std::size_t(d.class_id)]},
                     {"score", d.score},
                     {"x1", d.x1},
                     {"y1", d.y1},
                     {"x2", d.x2},
                     {"y2", d.y2}};
    if (i < angles.size()) b["angle"] = angles[i] ? nlohmann::json(*angles[i]) : nlohmann::json(nullptr);
    boxes.push_back(b);
  }
  return boxes;
}

}  // namespace cropsight::cli
