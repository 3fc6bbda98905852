// cropsight suggest: which frames of a broccoli sequence to label next, best first, by the model's
// uncertainty and the frames' diversity (pipeline/broccoli/suggest.hpp). Reads no labels; writes
// nothing. Scripts read --json; the studio ranks frames with the same library call.
#include <cstdio>

#include "broccoli_cli.hpp"
#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/pipeline/broccoli/suggest.hpp"

namespace cropsight::cli {

namespace suggest_cmd {
struct SuggestOptions {
  CommonOptions common;
  std::string data, model;
  pipeline::broccoli::SuggestConfig suggest;
  bool quiet = false;
};

nlohmann::json suggestion_json(const SuggestOptions& o, int total,
                               const std::vector<pipeline::broccoli::SuggestedFrame>& ranked) {
  nlohmann::json frames = nlohmann::json::array(), scores = nlohmann::json::array(),
                 uncertainty = nlohmann::json::array(), doubtful = nlohmann::json::array(),
                 heads = nlohmann::json::array();
  for (const auto& r : ranked) {
    frames.push_back(r.frame);
    scores.push_back(json_number(r.gain));
    uncertainty.push_back(json_number(r.measured.uncertainty));
    doubtful.push_back(r.measured.doubtful);
    heads.push_back(r.measured.heads);
  }
  return {{"data", o.data},
          {"model", o.model},
          {"total_frames", total},
          {"frames", frames},
          {"scores", scores},
          {"uncertainty", uncertainty},
          {"doubtful", doubtful},
          {"heads", heads},
          {"score_scale", o.suggest.score_scale},
          {"neighbour_frames", o.suggest.neighbour_frames},
          {"diversity_weight", o.suggest.diversity_weight},
          {"heads_weight", o.suggest.heads_weight}};
}

void run(const SuggestOptions& o) {
  if (o.suggest.frames < 1) throw Error("--frames", "must be >= 1, got " + std::to_string(o.suggest.frames));
  if (!(o.suggest.score_scale > 0)) throw Error("--score-scale", "must be > 0 (score units)");
  if (!(o.suggest.neighbour_frames > 0)) throw Error("--neighbour-frames", "must be > 0");
  if (!(o.suggest.heads_weight >= 0)) throw Error("--heads-weight", "must be >= 0");
  o.suggest.validate("--diversity");  // the one left: a weight in [0, 1]
  io::SequenceReader reader(o.data);
  if (reader.size() == 0) throw Error(o.data, "sequence has no frames to suggest from");
  const auto pipe = make_broccoli(o.model, o.common, /*track=*/false);
  Progress progress("suggest: " + o.data, reader.size(), o.quiet || o.common.json);
  const auto ranked =
      pipeline::broccoli::suggest_frames(*pipe, reader, o.suggest, [&](int done, int) { progress.update(done); });
  progress.finish();
  if (o.common.json) {
    print_json(suggestion_json(o, reader.size(), ranked));
    return;
  }
  std::printf("label these %zu of %d frames of %s first (model %s):\n", ranked.size(), reader.size(), o.data.c_str(),
              o.model.c_str());
  for (const auto& r : ranked)
    std::printf("  frame %4d  score %.3f  uncertainty %.3f  (%d of %d clusters near the threshold)\n", r.frame, r.gain,
                r.measured.uncertainty, r.measured.doubtful, r.measured.candidates);
}
}  // namespace suggest_cmd

void add_suggest(CLI::App& app) {
  using namespace suggest_cmd;
  auto o = std::make_shared<SuggestOptions>();
  auto* cmd = app.add_subcommand("suggest", "Rank a broccoli sequence's frames for labelling, best first");
  cmd->add_option("--data", o->data, "Sequence directory (labels are not read)")->required();
  add_broccoli_model_option(cmd, o->model);
  cmd->add_option("--frames", o->suggest.frames, "How many frames to suggest")->capture_default_str();
  cmd->add_option("--score-scale", o->suggest.score_scale,
                  "Score units: a cluster this far from the head threshold weighs 1/e")
      ->capture_default_str();
  cmd->add_option("--neighbour-frames", o->suggest.neighbour_frames,
                  "Frames: index gap at which a chosen frame's neighbours stop counting as alike (1/e)")
      ->capture_default_str();
  cmd->add_option("--diversity", o->suggest.diversity_weight,
                  "0 = uncertainty only, 1 = a frame like a chosen one gains nothing")
      ->capture_default_str();
  cmd->add_option("--heads-weight", o->suggest.heads_weight,
                  "Weight of a frame's predicted heads against its uncertainty (0 = uncertainty only)")
      ->capture_default_str();
  cmd->add_flag("--quiet", o->quiet, "No progress lines");
  add_config_options(cmd, o->common);
  add_json_flag(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
