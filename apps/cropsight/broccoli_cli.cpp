#include "broccoli_cli.hpp"

#include <cmath>
#include <sstream>

#include "cropsight/core/error.hpp"

namespace cropsight::cli {

std::vector<std::string> split_list(const std::string& text, const std::string& option) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string part; std::getline(in, part, ',');) {
    if (part.empty()) throw Error(option, "empty entry in list '" + text + "'");
    out.push_back(part);
  }
  if (out.empty()) throw Error(option, "expects at least one value");
  return out;
}

std::shared_ptr<const learning::Model> load_broccoli_model(const std::filesystem::path& path) {
  auto m = std::make_shared<learning::Model>(learning::load_model(path));
  if (m->info.task != pipeline::kBroccoliTask)
    throw Error(path.string(), "model was trained for task '" + m->info.task + "', not broccoli heads");
  return m;
}

nlohmann::json stages_json(const std::vector<StageTimer::Stage>& stages, long frames) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& s : stages) j[s.name] = frames > 0 ? s.total_ms / double(frames) : 0.0;
  return j;
}

namespace {
nlohmann::json num(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }
}  // namespace

nlohmann::json eval_json(const pipeline::BroccoliEvalResult& r) {
  const auto& c = r.confusion;
  nlohmann::json j;
  j["frames"] = r.frames;
  j["clusters"] = r.clusters;
  j["truth_heads"] = r.truth_heads;
  j["detections"] = r.detections;
  j["tp"] = c.tp;
  j["fp"] = c.fp;
  j["tn"] = c.tn;
  j["fn"] = c.fn;
  j["accuracy"] = num(c.accuracy());
  j["precision"] = num(c.precision());
  j["recall"] = num(c.recall());
  j["specificity"] = num(c.specificity());
  j["npv"] = num(c.npv());
  j["f1"] = num(c.f1());
  j["kappa"] = num(c.kappa());
  j["ap50"] = num(r.ap50);
  j["map50_95"] = num(r.map50_95);
  j["truth_heads_in_view"] = r.truth_heads_in_view;
  j["ap50_in_view"] = num(r.ap50_in_view);
  j["map50_95_in_view"] = num(r.map50_95_in_view);
  j["truth_heads_visible"] = r.truth_heads_visible;
  j["ap50_visible"] = num(r.ap50_visible);
  j["map50_95_visible"] = num(r.map50_95_visible);
  j["fps"] = num(r.fps());
  j["ms_per_frame"] = r.frames ? r.pipeline_ms / double(r.frames) : 0.0;
  j["stages_ms"] = stages_json(r.stages, r.frames);
  return j;
}

}  // namespace cropsight::cli
