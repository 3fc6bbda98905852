#include "broccoli_cli.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "cropsight/core/error.hpp"

namespace cropsight::cli {

std::unique_ptr<pipeline::broccoli::Pipeline> make_broccoli(const std::string& model, const CommonOptions& common,
                                                            bool track) {
  pipeline::PipelineSpec spec{common.config, common.sets, model};
  spec.sets.push_back(track ? "track=true" : "track=false");
  return pipeline::broccoli::make_pipeline(spec);
}

void add_broccoli_model_option(CLI::App* cmd, std::string& model) {
  model = pipeline::broccoli::kDefaultModel;
  cmd->add_option("--model", model,
                  "Model: a shipped model's name (models/, e.g. broccoli-oes-uk) or a file written by train broccoli")
      ->capture_default_str();
}

void add_track_options(CLI::App* cmd, TrackOptions& o, bool detect) {
  cmd->add_flag("--track", o.track,
                "Size every detection and run the temporal filter (keys sizing.*, tracking.* of the preset)");
  if (detect) {
    cmd->add_option("--map", o.map, "With --track: write the field map CSV (id, x, y, z, diameters, frames, ...)");
  } else {
    cmd->add_option("--map-min-points", o.map_min_points,
                    "With --track: a true head counts for map recall when a frame shows it with at least this "
                    "many valid points (default 300)");
    cmd->add_flag("--fit-size-bias", o.fit_size_bias,
                  "With --track: fit the size bias correction (scale, offset) of both estimators on these "
                  "sequences (use training data) and print the sizing.* values");
  }
}

nlohmann::json pipeline_json(const pipeline::PipelineTiming& t, const pipeline::PipelineTiming* pcl) {
  nlohmann::json j{{"ms_per_frame", t.ms_per_frame()},
                   {"fps", t.fps()},
                   {"cpu_ms_per_frame", t.cpu_ms_per_frame()},
                   {"cpu_fps", t.cpu_fps()},
                   {"clusters_per_frame", t.clusters_per_frame()},
                   {"stages_ms", stages_json(t.stages, t.frames)}};
  if (pcl) {
    j["speedup_vs_pcl"] = t.ms_per_frame() > 0 ? pcl->ms_per_frame() / t.ms_per_frame() : 0.0;
    j["cpu_speedup_vs_pcl"] = t.cpu_ms_per_frame() > 0 ? pcl->cpu_ms_per_frame() / t.cpu_ms_per_frame() : 0.0;
  }
  return j;
}

nlohmann::json tracking_timing_json(const pipeline::PipelineTiming& t, const pipeline::PipelineTiming& oes,
                                    const tracking::HeadMapperConfig& cfg) {
  const auto& sz = cfg.sizing;
  return {{"ms_per_frame", t.ms_per_frame()},
          {"cpu_ms_per_frame", t.cpu_ms_per_frame()},
          {"detections_per_frame", t.clusters_per_frame()},
          {"ratio_to_oes", oes.ms_per_frame() > 0 ? t.ms_per_frame() / oes.ms_per_frame() : 0.0},
          {"cpu_ratio_to_oes", oes.cpu_ms_per_frame() > 0 ? t.cpu_ms_per_frame() / oes.cpu_ms_per_frame() : 0.0},
          {"sizing",
           {{"estimator", sz.estimator},
            {"compute_hull", sz.compute_hull},
            {"hull_engine", sz.hull_engine},
            {"hull_max_points", sz.hull_max_points}}},
          {"use_poses", cfg.tracking.use_poses}};
}

}  // namespace cropsight::cli
