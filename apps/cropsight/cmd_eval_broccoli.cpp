// cropsight eval broccoli: runs the detector of a model over labelled sequences and prints the
// cluster confusion metrics (Table I of Montes et al. 2020), AP50 and mAP50:95 on point sets
// (Table II) and the pipeline's speed (frames are read before timing; I/O is excluded).
#include <cmath>
#include <cstdio>
#include <optional>

#include "broccoli_cli.hpp"
#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/pipeline/broccoli/eval.hpp"
#include "cropsight/pipeline/broccoli/tracking_eval.hpp"
#include "cropsight/pipeline/broccoli/training.hpp"

namespace cropsight::cli {

namespace eval_broccoli_cmd {
struct EvalOptions {
  CommonOptions common;
  std::string data, model;
  bool quiet = false;
  TrackOptions track;  // --track, --fit-size-bias, --map-min-points
};

void run(const EvalOptions& o) {
  if (o.track.fit_size_bias && !o.track.track) throw Error("--fit-size-bias", "needs --track");
  if (o.track.map_min_points < 0) throw Error("--map-min-points", "must be >= 0 (0: every true head counts)");
  const auto built = make_broccoli(o.model, o.common, o.track.track);
  pipeline::broccoli::Pipeline& pipe = *built;
  pipeline::broccoli::Evaluator evaluator(pipe);
  std::optional<pipeline::broccoli::TrackingEvaluator> tracker;
  if (o.track.track)
    tracker.emplace(pipeline::broccoli::TrackingEvalOptions{o.track.map_min_points, o.track.fit_size_bias, {}});
  for (const auto& dir : split_list(o.data, "--data")) {
    io::SequenceReader reader(dir);
    if (!reader.info().has_labels) throw Error(dir, "sequence has no labels/ (evaluation needs ground truth)");
    // The map and size figures compare with groundtruth.json; without it they would read 0.
    if (tracker && !reader.info().has_groundtruth)
      throw Error(dir, "sequence has no groundtruth.json (--track evaluates the map and sizes against it)");
    Progress progress("eval broccoli: " + dir, reader.size(), o.quiet || o.common.json);
    pipe.reset();
    if (tracker) tracker->begin_pass(reader.groundtruth(), !reader.poses().empty(), dir);
    for (int i = 0; i < reader.size(); ++i) {
      const RgbdFrame frame = reader.read(i);  // read outside the timed section
      evaluator.add_frame(frame);              // the pipeline's steps on this frame, then Table I / II
      if (tracker) tracker->add_frame(frame, pipe);
      progress.update(i + 1);
    }
    if (tracker) tracker->end_pass(pipe);
    progress.finish();
  }
  const auto r = evaluator.figures();
  nlohmann::json j = eval_json(r);
  j["model"] = o.model;
  j["data"] = o.data;
  j["pipeline"] = config_name(pipe.config().detector.pipeline);
  j["features"] = pipe.config().detector.features;
  j["classifier"] = pipe.detector().model()->params.type;
  std::optional<pipeline::broccoli::TrackingFigures> figures;
  if (tracker) j.update(tracking_json(*(figures = tracker->figures())));
  if (o.common.json) {
    print_json(j);
    return;
  }
  print_eval_summary(o.model, o.data, r);
  if (figures) print_tracking_summary(*figures);
}
}  // namespace eval_broccoli_cmd

void add_eval_broccoli(CLI::App& eval) {
  using namespace eval_broccoli_cmd;
  auto o = std::make_shared<EvalOptions>();
  auto* cmd = eval.add_subcommand("broccoli", "Evaluate a broccoli head model on labelled sequences");
  cmd->add_option("--data", o->data, "Sequence directories, comma separated")->required();
  add_broccoli_model_option(cmd, o->model);
  cmd->add_flag("--quiet", o->quiet, "No progress lines");
  add_track_options(cmd, o->track, /*detect=*/false);
  add_config_options(cmd, o->common);
  add_json_flag(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
