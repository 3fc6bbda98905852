// cropsight segment grape: labels every point of a text cloud with a trained model and writes
// the cloud back in the dataset's format with the predicted label in the last column.
//
//   cropsight segment grape --model MODEL --input CLOUD.txt --out LABELLED.txt
//                           [--sampled [--sampling random|fps] [--carry-k K]] [--json]
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/grape_text.hpp"
#include "cropsight/pipeline/grape_model.hpp"

namespace cropsight::cli {
namespace {
struct SegmentGrapeOptions {
  CommonOptions common;
  std::string model, input, out;
  int threads = 2;
  bool sampled = false;
  std::string sampling = "random";
  int carry_k = 4;  // the fast GBDT's colour-guided vote; 1 = the paper's nearest neighbour
};

void run(const SegmentGrapeOptions& o) {
  auto model = pipeline::GrapeModel::load(o.model, o.threads);
  if (o.sampling != "random" && o.sampling != "fps")
    throw Error("--sampling", "expected random or fps, got '" + o.sampling + "'");
  model.set_sampled(o.sampled, o.sampling == "fps", o.carry_k);
  Cloud cloud = io::read_grape_text(o.input);
  const auto t0 = std::chrono::steady_clock::now();
  cloud.labels = model.segment(cloud);
  const double ms = 1000.0 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  io::write_grape_text(o.out, cloud);
  std::vector<long> counts(6, 0);
  for (int l : cloud.labels)
    if (l >= 0 && l < 6) ++counts[std::size_t(l)];
  if (o.common.json) {
    print_json({{"input", o.input},
                {"out", o.out},
                {"points", cloud.size()},
                {"label_counts", counts},
                {"ms", ms},
                {"mode", o.sampled ? "sampled" : "every-point"}});
  } else {
    std::printf("%zu points labelled in %.1f ms -> %s\n", cloud.size(), ms, o.out.c_str());
  }
}
}  // namespace

void add_segment_grape(CLI::App& segment) {
  auto o = std::make_shared<SegmentGrapeOptions>();
  auto* cmd = segment.add_subcommand("grape", "Label every point of a grape text cloud");
  cmd->add_option("--model", o->model, "Model file (gbdt .json or network .pt)")->required();
  cmd->add_option("--input", o->input, "Text cloud (x y z nx ny nz r g b [label])")->required();
  cmd->add_option("--out", o->out, "Labelled text cloud to write")->required();
  cmd->add_option("--threads", o->threads, "Threads (default 2)");
  cmd->add_flag("--sampled", o->sampled,
                "Networks: the paper's mode, one pass on num_points samples, labels carried back to the other points "
                "(--carry-k; default: a prediction for every point)");
  cmd->add_option("--sampling", o->sampling, "With --sampled: random (as in training, default) or fps");
  cmd->add_option("--carry-k", o->carry_k,
                  "With --sampled: samples voting for each other point, weighted by distance and colour (default 4; 1 "
                  "= nearest, the paper)");
  add_json_flag(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
