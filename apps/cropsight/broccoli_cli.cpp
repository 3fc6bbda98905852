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

}  // namespace cropsight::cli
