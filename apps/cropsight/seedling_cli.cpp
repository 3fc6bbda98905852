#include "seedling_cli.hpp"

#include <utility>

namespace cropsight::cli {

pipeline::SeedlingPipeline seedling_pipeline(const CommonOptions& o) {
  pipeline::SeedlingConfig cfg;
  apply_checked_config(cfg, o, "seedling", pipeline::validate_seedling_config);
  return pipeline::SeedlingPipeline(std::move(cfg), o.config.empty() ? "configs/seedling.yaml" : o.config);
}

nlohmann::json seedling_json(const pipeline::SeedlingDetection& d) {
  nlohmann::json t = nlohmann::json::object();
  for (const auto& s : d.timer.stages()) t[s.name] = s.total_ms;
  t["total"] = d.timer.total_ms();
  return {
      {"found", d.found},
      {"envelope",
       {{"length_m", d.envelope.length},
        {"width_m", d.envelope.width},
        {"height_m", d.envelope.height},
        {"volume_m3", d.envelope.volume()}}},
      {"top_view_area_m2", d.top_view.area()},
      {"plane", {{"normal", {d.plane_normal.x(), d.plane_normal.y(), d.plane_normal.z()}}, {"d", d.plane_d}}},
      {"points",
       {{"reconstructed", d.points_total},
        {"above_soil", d.points_candidates},
        {"sampled", d.points_sampled},
        {"seedling_sampled", d.points_seedling_sampled},
        {"seedling_dense", int(d.points.size())}}},
      {"gmm", {{"components", d.gmm.model.size()}, {"iterations", d.gmm.iterations}, {"chosen", d.chosen_components}}},
      {"timings_ms", t}};
}

nlohmann::json seedling_evaluation_json(const pipeline::SeedlingEvaluation& e) {
  nlohmann::json per = nlohmann::json::array();
  for (const auto& r : e.per_pair)
    per.push_back({{"pair", r.pair},
                   {"iou", r.score.iou},
                   {"sensitivity", r.score.sensitivity},
                   {"volume_ratio", r.score.volume_ratio},
                   {"ms", r.ms},
                   {"gmm_iterations", r.gmm_iterations}});
  nlohmann::json j = {{"pairs", e.pairs},
                      {"recognition_rate", e.recognition_rate},
                      {"sensitivity", e.sensitivity},
                      {"volume_ratio", e.volume_ratio},
                      {"ms_total", e.ms_total},
                      {"ms_sgm", e.ms_sgm},
                      {"ms_gmm", e.ms_gmm},
                      {"per_pair", per}};
  if (e.opencv_runs) {
    j["ms_gmm_opencv"] = e.ms_gmm_opencv;
    j["gmm_mean_log_likelihood"] = e.gmm_mean_log_likelihood;
    j["gmm_opencv_mean_log_likelihood"] = e.gmm_opencv_mean_log_likelihood;
  }
  return j;
}

}  // namespace cropsight::cli
