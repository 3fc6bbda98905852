// cropsight segment grape: labels every point of grape clouds with a grape segmenter
// (pipeline::grape::Segmenter: a preset, or --model and the mode flags), the model loaded once for
// every cloud, and writes each cloud back with the predicted label (pipeline/grape/cloud_files.hpp).
//
//   cropsight segment grape [--config PRESET] [--model MODEL] --clouds FILE|DIR|A,B,... --out FILE|DIR
//                           [--format txt|ply|pcd] [--sampled ...] [--votes N] [--ensemble MODEL2] [--json]
//
// One cloud file: --out is the labelled file (its extension chooses the format). A folder or a
// list: --out is a new folder of <stem>.<format>. Without --config and --model the shipped best
// recipe runs (configs/grape-best.yaml). Start-up (model load) and per-cloud times are reported apart.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/core/threads.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/io/file_names.hpp"
#include "cropsight/io/output.hpp"
#include "cropsight/pipeline/grape/cloud_files.hpp"
#include "cropsight/pipeline/grape/segmenter.hpp"
#include "cropsight/pipeline/grape/truth.hpp"
#include "grape_segmenter_options.hpp"

namespace cropsight::cli {
namespace segment_grape_cmd {
namespace fs = std::filesystem;

struct SegmentGrapeOptions {
  CommonOptions common;
  std::string clouds, out, format;
  int threads = 2;
  bool force = false, quiet = false;
  GrapeSegmenterOptions segmenter;
};

// Where each labelled cloud goes, checked before the model loads: one file, or a new folder whose
// names must not collide (a.txt and a.ply would both become a.<format>).
struct Outputs {
  std::unique_ptr<io::OutputFolder> folder;
  std::vector<fs::path> paths;
};

Outputs plan_outputs(const SegmentGrapeOptions& o, const std::vector<fs::path>& files, const io::OutputPolicy& policy) {
  const bool one = files.size() == 1 && !fs::is_directory(o.clouds) && o.clouds.find(',') == std::string::npos;
  Outputs out;
  if (one) {
    if (!o.format.empty())
      throw Error("--format", "is for several clouds; with one, the --out file's extension chooses");
    io::check_output_file(o.out, policy);
    const std::string ext = io::lower_extension(o.out);
    if (ext != ".txt" && ext != ".ply" && ext != ".pcd")
      throw Error(o.out, "unknown cloud format '" + ext + "' (expected .txt, .ply or .pcd)");
    out.paths.push_back(o.out);
    return out;
  }
  std::string format = o.format;
  if (format.empty())
    format = std::all_of(files.begin(), files.end(), [](const fs::path& f) { return io::lower_extension(f) == ".txt"; })
                 ? "txt"
                 : "ply";
  if (format != "txt" && format != "ply" && format != "pcd")
    throw Error("--format", "expected txt, ply or pcd, got '" + format + "'");
  std::set<std::string> names;
  for (const fs::path& f : files)
    if (!names.insert(f.stem().string()).second)
      throw Error(f.string(), "two clouds named '" + f.stem().string() + "' would write the same output file");
  out.folder = std::make_unique<io::OutputFolder>(o.out, policy);
  for (const fs::path& f : files) out.paths.push_back(out.folder->path() / (f.stem().string() + "." + format));
  return out;
}

void run(const SegmentGrapeOptions& o) {
  if (o.clouds.empty()) throw Error("--clouds", "give the clouds to label");
  check_thread_count(o.threads, "--threads");
  auto cfg = o.segmenter.config();
  const std::vector<fs::path> files = pipeline::grape::list_cloud_files(o.clouds);
  Outputs out = plan_outputs(o, files, output_policy("segment grape", o.force, {o.clouds, cfg.model, cfg.ensemble}));
  cfg.threads = o.threads;
  const Stopwatch startup;
  const pipeline::grape::Segmenter segmenter(cfg, "command line");
  const double startup_ms = startup.ms();
  nlohmann::json clouds = nlohmann::json::array();
  double total_ms = 0;
  Progress progress("segment grape", long(files.size()), o.quiet || o.common.json || !out.folder);
  for (std::size_t i = 0; i < files.size(); ++i) {
    pipeline::grape::SegmentInput in = pipeline::grape::read_segment_input(files[i]);
    const Stopwatch clock;
    in.original.labels = segmenter.segment(in.model_view);
    const double ms = clock.ms();
    total_ms += ms;
    pipeline::grape::write_labelled_cloud(out.paths[i], in.original);
    const fs::path shown = out.folder ? out.folder->final_path() / out.paths[i].filename() : out.paths[i];
    clouds.push_back({{"input", files[i].string()},
                      {"out", shown.string()},
                      {"points", in.original.size()},
                      {"label_counts", pipeline::grape::label_counts(in.original)},
                      {"ms", json_number(ms)}});
    if (!o.common.json && !out.folder)
      std::printf("%zu points labelled in %.1f ms -> %s\n", in.original.size(), ms, o.out.c_str());
    progress.update(long(i + 1));
  }
  progress.finish();
  if (out.folder) out.folder->commit("labelled clouds");
  const double mean_ms = total_ms / double(files.size());
  if (o.common.json) {
    nlohmann::json j = out.folder ? nlohmann::json{{"out", o.out}, {"clouds", clouds}} : clouds[0];
    j["startup_ms"] = json_number(startup_ms);
    j["mean_ms"] = json_number(mean_ms);
    j["mode"] = segmenter.mode();
    GrapeSegmenterOptions::describe(cfg, j);
    print_json(j);
  } else if (out.folder) {
    std::printf("%zu clouds labelled -> %s: %.1f ms a cloud (mean), start-up %.1f ms (model load)\n", files.size(),
                o.out.c_str(), mean_ms, startup_ms);
  }
}
}  // namespace segment_grape_cmd

void add_segment_grape(CLI::App& segment) {
  using namespace segment_grape_cmd;
  auto o = std::make_shared<SegmentGrapeOptions>();
  auto* cmd = segment.add_subcommand("grape", "Label every point of grape clouds (one model load for all)");
  cmd->add_option("--clouds", o->clouds,
                  "Cloud files: one, a folder or a comma list; .txt in the dataset's format (10 numbers a line: x y z "
                  "nx ny nz r g b label, unit scale; the label is not used) or .ply / .pcd in metres with colour");
  add_deprecated_option(cmd, "--input", o->clouds, "--clouds");
  cmd->add_option("--out", o->out, "One cloud: the labelled file (.txt, .ply, .pcd); several: a new folder")
      ->required();
  cmd->add_option("--format", o->format, "Several clouds: txt | ply | pcd (default: txt for text inputs, else ply)");
  add_force_flag(cmd, o->force);
  cmd->add_option("--threads", o->threads, "Threads, 1.." + std::to_string(kMaxThreads) + " (default 2)");
  cmd->add_flag("--quiet", o->quiet, "No progress lines");
  o->segmenter.add_options(cmd, "grape-best");
  add_json_flag(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
