#include "seedling_cli.hpp"

#include <utility>

#include "cropsight/pipeline/seedling/make_pipeline.hpp"

namespace cropsight::cli {

pipeline::seedling::Pipeline seedling_pipeline(const CommonOptions& o) {
  return std::move(*pipeline::seedling::make_pipeline({o.config, o.sets}));
}

nlohmann::json seedling_json(const pipeline::seedling::FrameResult& d) {
  nlohmann::json t = nlohmann::json::object();
  for (const auto& s : d.timer.stages()) t[s.name] = json_number(s.total_ms);
  t["total"] = json_number(d.timer.total_ms());
  return {
      {"found", d.found},
      {"envelope",
       {{"length_m", json_number(d.envelope.length)},
        {"width_m", json_number(d.envelope.width)},
        {"height_m", json_number(d.envelope.height)},
        {"volume_m3", json_number(d.envelope.volume())}}},
      {"top_view_area_m2", json_number(d.top_view.area())},
      {"plane",
       {{"normal", {d.plane_normal.x(), d.plane_normal.y(), d.plane_normal.z()}}, {"d", json_number(d.plane_d)}}},
      {"points",
       {{"reconstructed", d.points_total},
        {"above_soil", d.points_candidates},
        {"sampled", d.points_sampled},
        {"seedling_sampled", d.points_seedling_sampled},
        {"seedling_dense", int(d.points.size())}}},
      {"gmm", {{"components", d.gmm.model.size()}, {"iterations", d.gmm.iterations}, {"chosen", d.chosen_components}}},
      {"timings_ms", t}};
}

nlohmann::json seedling_evaluation_json(const pipeline::seedling::Figures& e) {
  nlohmann::json per = nlohmann::json::array();
  for (const auto& r : e.per_pair)
    per.push_back({{"pair", r.pair},
                   {"iou", json_number(r.score.iou)},
                   {"sensitivity", json_number(r.score.sensitivity)},
                   {"volume_ratio", json_number(r.score.volume_ratio)},
                   {"ms", json_number(r.ms)},
                   {"gmm_iterations", r.gmm_iterations}});
  nlohmann::json j = {{"pairs", e.pairs},
                      {"recognition_rate", json_number(e.recognition_rate)},
                      {"sensitivity", json_number(e.sensitivity)},
                      {"volume_ratio", json_number(e.volume_ratio)},
                      {"ms_total", json_number(e.ms_total)},
                      {"ms_sgm", json_number(e.ms_sgm)},
                      {"ms_gmm", json_number(e.ms_gmm)},
                      {"per_pair", per}};
  if (e.opencv_runs) {
    j["ms_gmm_opencv"] = json_number(e.ms_gmm_opencv);
    j["gmm_mean_log_likelihood"] = json_number(e.gmm_mean_log_likelihood);
    j["gmm_opencv_mean_log_likelihood"] = json_number(e.gmm_opencv_mean_log_likelihood);
  }
  return j;
}

}  // namespace cropsight::cli
