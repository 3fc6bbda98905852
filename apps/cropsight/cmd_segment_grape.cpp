// cropsight segment grape: labels every point of a text cloud with a trained model and writes
// the cloud back in the dataset's format with the predicted label in the last column.
//
//   cropsight segment grape --model MODEL --input CLOUD.txt --out LABELLED.txt
//                           [--sampled [--sampling random|fps] [--carry-k K]] [--votes N]
//                           [--ensemble MODEL2 [--ensemble-weight W]] [--json]
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/core/threads.hpp"
#include "cropsight/io/grape_text.hpp"
#include "cropsight/pipeline/grape_model.hpp"
#include "grape_network_mode.hpp"

namespace cropsight::cli {
namespace {
struct SegmentGrapeOptions {
  CommonOptions common;
  std::string model, input, out;
  int threads = 2;
  GrapeNetworkMode mode;
};

void run(const SegmentGrapeOptions& o) {
  check_thread_count(o.threads, "--threads");
  if (std::filesystem::is_directory(o.out)) throw Error(o.out, "is a directory, expected a file name");
  auto model = pipeline::GrapeModel::load(o.model, o.threads);
  o.mode.apply(model, o.threads);
  Cloud cloud = io::read_grape_text(o.input);
  const auto t0 = std::chrono::steady_clock::now();
  cloud.labels = model.segment(cloud);
  const double ms = 1000.0 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  io::write_grape_text(o.out, cloud);
  std::vector<long> counts(6, 0);
  for (int l : cloud.labels)
    if (l >= 0 && l < 6) ++counts[std::size_t(l)];
  if (o.common.json) {
    nlohmann::json j = {{"input", o.input},       {"out", o.out}, {"points", cloud.size()},
                        {"label_counts", counts}, {"ms", ms},     {"mode", o.mode.name()}};
    o.mode.describe(j);
    print_json(j);
  } else {
    std::printf("%zu points labelled in %.1f ms -> %s\n", cloud.size(), ms, o.out.c_str());
  }
}
}  // namespace

void add_segment_grape(CLI::App& segment) {
  auto o = std::make_shared<SegmentGrapeOptions>();
  auto* cmd = segment.add_subcommand("grape", "Label every point of a grape text cloud");
  cmd->add_option("--model", o->model, "Model file (gbdt .json or network .pt)")->required();
  cmd->add_option(
         "--input", o->input,
         "Text cloud in the dataset's format: x y z nx ny nz r g b label (10 numbers a line; the label is read but "
         "not used)")
      ->required();
  cmd->add_option("--out", o->out, "Labelled text cloud to write")->required();
  cmd->add_option("--threads", o->threads, "Threads, 1.." + std::to_string(kMaxThreads) + " (default 2)");
  o->mode.add_options(cmd);
  add_json_flag(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
