#include "grape_cli.hpp"

#include "cli_common.hpp"

namespace cropsight::cli {

nlohmann::json grape_evaluation_json(const pipeline::GrapeEvaluation& e) {
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
  for (const auto& p : pipeline::grape_protocols(e))
    j["protocols"][p.name] = {{"classes", p.classes}, {"miou", json_number(p.miou)}};
  return j;
}

}  // namespace cropsight::cli
