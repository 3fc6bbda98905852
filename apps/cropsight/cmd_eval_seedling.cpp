// cropsight eval seedling: runs the seedling pipeline over a simulated data set
// (cropsight simulate seedling) and prints recognition rate (top-view IoU >= 0.5), sensitivity,
// envelope volume ratio and timings; cv::ml::EM is timed on the same down-sampled points as our
// GMM (same K, tolerance and iteration cap). The evaluation is the library's
// (pipeline::seedling::evaluate_seedling_dataset); this file parses options and formats its figures.
#include <cstdio>

#include "commands.hpp"
#include "seedling_cli.hpp"

namespace cropsight::cli {

namespace eval_seedling_cmd {

struct Options {
  CommonOptions common;
  std::string data, calib;
  bool quiet = false, no_opencv = false;
};

void print_text(const pipeline::seedling::Figures& e) {
  std::printf("pairs %d: recognition %.1f%%, sensitivity %.1f%%, volume ratio %.1f%%\n", e.pairs,
              100 * e.recognition_rate, 100 * e.sensitivity, 100 * e.volume_ratio);
  std::printf("ms per pair: total %.1f, SGM %.1f, GMM %.2f", e.ms_total, e.ms_sgm, e.ms_gmm);
  if (e.opencv_runs) std::printf(", cv::ml::EM on the same points %.2f", e.ms_gmm_opencv);
  std::printf("\n");
}

void run(const Options& o) {
  const auto seedlings = seedling_pipeline(o.common);
  const auto data = pipeline::seedling::open_dataset(o.data, o.calib);
  Progress progress("eval seedling", long(data.pairs.size()), o.quiet || o.common.json);
  pipeline::seedling::Evaluator::Options eo;
  eo.compare_opencv_em = !o.no_opencv;
  const auto e =
      pipeline::seedling::evaluate_seedling_dataset(data, seedlings, eo, [&](int done) { progress.update(done); });
  progress.finish();
  if (o.common.json)
    print_json(seedling_evaluation_json(e));
  else
    print_text(e);
}

}  // namespace eval_seedling_cmd

void add_eval_seedling(CLI::App& eval) {
  using namespace eval_seedling_cmd;
  auto o = std::make_shared<Options>();
  auto* cmd = eval.add_subcommand("seedling", "Seedling recognition on simulated stereo pairs");
  cmd->add_option("--data", o->data, "Folder written by cropsight simulate seedling")->required();
  cmd->add_option("--calib", o->calib, "Calibration YAML (default: DATA/rig.yaml)");
  cmd->add_flag("--no-opencv", o->no_opencv, "Skip timing cv::ml::EM on the same points");
  cmd->add_flag("--quiet", o->quiet, "No progress line");
  add_json_flag(cmd, o->common);
  add_config_options(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
