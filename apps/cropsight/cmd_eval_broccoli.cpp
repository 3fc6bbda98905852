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
  const auto& c = r.confusion;
  std::printf("%s on %s: %ld frames, %ld clusters (%lld heads by the majority rule)\n", o.model.c_str(), o.data.c_str(),
              r.frames, r.clusters, static_cast<long long>(c.positives()));
  std::printf("  TP %lld  FP %lld  TN %lld  FN %lld\n", static_cast<long long>(c.tp), static_cast<long long>(c.fp),
              static_cast<long long>(c.tn), static_cast<long long>(c.fn));
  std::printf("  accuracy %.4f  precision %.4f  recall %.4f  specificity %.4f  npv %.4f  kappa %.4f\n", c.accuracy(),
              c.precision(), c.recall(), c.specificity(), c.npv(), c.kappa());
  std::printf("  AP50 %.4f  mAP50:95 %.4f  (%lld labelled heads)\n", r.ap50, r.map50_95,
              static_cast<long long>(r.truth_heads));
  std::printf("  AP50 %.4f  mAP50:95 %.4f  in view (%lld heads not cut by the border)\n", r.ap50_in_view,
              r.map50_95_in_view, static_cast<long long>(r.truth_heads_in_view));
  std::printf("  AP50 %.4f  mAP50:95 %.4f  visible (%lld heads with >= detection.visible_truth_points points)\n",
              r.ap50_visible, r.map50_95_visible, static_cast<long long>(r.truth_heads_visible));
  std::printf(
      "  AP50 %.4f  visible %.4f  at any depth (%lld / %lld heads the sensor measured, in or out of the window)\n",
      r.ap50_any_depth, r.ap50_visible_any_depth, static_cast<long long>(r.truth_heads_any_depth),
      static_cast<long long>(r.truth_heads_visible_any_depth));
  std::printf("  %.1f fps (%.2f ms/frame, pipeline only)\n", r.fps(), r.ms_per_frame());
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
