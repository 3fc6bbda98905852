#pragma once
// Helpers shared by the broccoli sub-commands (train / detect / eval / bench broccoli, report
// --model): building the pipeline from a model and the preset, and formatting the library's
// results (text or JSON). Nothing here computes a result.
#include <CLI/CLI.hpp>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/learning/model.hpp"
#include "cropsight/pipeline/broccoli/eval.hpp"
#include "cropsight/pipeline/broccoli/make_pipeline.hpp"
#include "cropsight/pipeline/broccoli/pipeline.hpp"
#include "cropsight/pipeline/broccoli/tracking_eval.hpp"
#include "cropsight/pipeline/broccoli/training.hpp"

namespace cropsight::cli {

/// The pipeline of --model (a shipped model's name or a file), --config, --set and --track, built
/// by the library's one builder (pipeline::broccoli::make_pipeline).
std::unique_ptr<pipeline::broccoli::Pipeline> make_broccoli(const std::string& model, const CommonOptions& common,
                                                            bool track);
/// --model NAME|FILE of the broccoli commands, defaulting to kDefaultBroccoliModel.
void add_broccoli_model_option(CLI::App* cmd, std::string& model);

/// --track (both) and --map (detect) or --map-min-points / --fit-size-bias (eval).
struct TrackOptions {
  bool track = false;
  std::string map;             ///< detect: --map FILE
  bool fit_size_bias = false;  ///< eval: fit the size bias correction on the evaluated data
  int map_min_points = 300;    ///< eval: true heads count for the map when seen with this many points
};
void add_track_options(CLI::App* cmd, TrackOptions& o, bool detect);

/// Per-stage milliseconds per frame as JSON {"cloud": 1.2, ...}.
nlohmann::json stages_json(const std::vector<StageMs>& stages);

/// Table I + II metrics of an evaluation as JSON (NaN → null).
nlohmann::json eval_json(const pipeline::broccoli::Figures& r);
/// The evaluation as text: the operating point first (precision, recall, F1, kappa at the model's
/// own threshold; "no detection at all" said in the summary line when the model accepted nothing),
/// then AP, named for what it is: a ranking of every candidate cluster, rejected ones included.
void print_eval_summary(const std::string& model, const std::string& data, const pipeline::broccoli::Figures& r);

/// The tracking figures as the keys of `eval broccoli --track --json` (NaN → null).
/// ap50_temporal / map50_95_temporal are the offline figures under their earlier names.
nlohmann::json tracking_json(const pipeline::broccoli::TrackingFigures& f);

/// One detection of `detect broccoli`'s JSON lines (id = 1-based number in the frame).
nlohmann::json detection_json(const Detection& d, int id);

/// detect --track: adds "heads" [{id, track_id, diameter_mm, bbox_mm, hull_mm, harvestable,
/// field}], "predicted" [{track_id, points, centroid}] and "camera_estimate" to a frame's line.
void add_tracking_json(const pipeline::broccoli::FrameResult& r, const tracking::HeadMapper& mapper,
                       nlohmann::json& line);

/// Human-readable lines of the tracking figures.
void print_tracking_summary(const pipeline::broccoli::TrackingFigures& f);

}  // namespace cropsight::cli
