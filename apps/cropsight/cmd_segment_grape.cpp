// cropsight segment grape: labels every point of a text cloud with a grape segmenter
// (pipeline::grape::Segmenter: a preset, or --model and the mode flags) and writes the cloud back in
// the dataset's format with the predicted label in the last column.
//
//   cropsight segment grape [--config PRESET] [--model MODEL] --input CLOUD.txt --out LABELLED.txt
//                           [--sampled [--sampling random|fps] [--carry-k K]] [--votes N]
//                           [--ensemble MODEL2 [--ensemble-weight W]] [--json]
//
// Without --config and --model the shipped best recipe runs (configs/grape-best.yaml).
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/core/threads.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/io/grape_text.hpp"
#include "cropsight/pipeline/grape/segmenter.hpp"
#include "cropsight/pipeline/grape/truth.hpp"
#include "grape_segmenter_options.hpp"

namespace cropsight::cli {
namespace segment_grape_cmd {
struct SegmentGrapeOptions {
  CommonOptions common;
  std::string input, out;
  int threads = 2;
  bool force = false;
  GrapeSegmenterOptions segmenter;
};

void run(const SegmentGrapeOptions& o) {
  if (o.input.empty()) throw Error("--clouds", "give the text cloud to label");
  check_thread_count(o.threads, "--threads");
  auto cfg = o.segmenter.config();
  io::check_output_file(o.out, output_policy("segment grape", o.force, {o.input, cfg.model, cfg.ensemble}));
  cfg.threads = o.threads;
  const pipeline::grape::Segmenter segmenter(cfg, "command line");
  Cloud cloud = io::read_grape_text(o.input);
  const Stopwatch clock;
  cloud.labels = segmenter.segment(cloud);
  const double ms = clock.ms();
  io::write_grape_text(o.out, cloud);
  if (o.common.json) {
    nlohmann::json j = {{"input", o.input},       {"out", o.out},
                        {"points", cloud.size()}, {"label_counts", pipeline::grape::label_counts(cloud)},
                        {"ms", json_number(ms)},  {"mode", segmenter.mode()}};
    GrapeSegmenterOptions::describe(cfg, j);
    print_json(j);
  } else {
    std::printf("%zu points labelled in %.1f ms -> %s\n", cloud.size(), ms, o.out.c_str());
  }
}
}  // namespace segment_grape_cmd

void add_segment_grape(CLI::App& segment) {
  using namespace segment_grape_cmd;
  auto o = std::make_shared<SegmentGrapeOptions>();
  auto* cmd = segment.add_subcommand("grape", "Label every point of a grape text cloud");
  cmd->add_option("--clouds", o->input,
                  "Text cloud in the dataset's format: x y z nx ny nz r g b label (10 numbers a line; the label is "
                  "read but not used)");
  add_deprecated_option(cmd, "--input", o->input, "--clouds");
  cmd->add_option("--out", o->out, "Labelled text cloud to write")->required();
  add_force_flag(cmd, o->force);
  cmd->add_option("--threads", o->threads, "Threads, 1.." + std::to_string(kMaxThreads) + " (default 2)");
  o->segmenter.add_options(cmd, "grape-best");
  add_json_flag(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
