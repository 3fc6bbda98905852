// cropsight bench potato: the potato loop (detect, locate, ripeness, select / track,
// orient) timed per stage, single-threaded, on frames in memory, for each preset asked, beside an
// RGB -> Lab conversion of the same frames timed in the same process (the ratio is the figure
// that holds on a noisy machine). Without --data it simulates one approach (scene sheet, 640x480)
// into a temporary folder (io::TempDirectory) that is removed afterwards. The timing is the library's
// (pipeline/potato/timing.hpp); this file picks frames and presets and prints.
#include <oneapi/tbb/global_control.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/pipeline/potato/make_pipeline.hpp"
#include "cropsight/pipeline/potato/timing.hpp"
#include "cropsight/sim/potato/potato_sim.hpp"

namespace cropsight::cli {

namespace bench_potato_cmd {
namespace pp = pipeline::potato;
using pipeline::PipelineTiming;

struct BenchPotatoOptions {
  CommonOptions common;
  std::string data, presets = "potato", scene = "sheet";
  int frames = 0, repeat = 3;
  std::uint64_t seed = 1;
  bool quiet = false;
};

std::vector<RgbdFrame> with_colour(std::vector<RgbdFrame> frames, const std::string& dir) {
  if (frames.front().color.empty()) throw Error(dir, "the potato loop needs colour images");
  return frames;
}

// --data's frames, or one simulated approach in `scratch` (a temporary folder never committed, so
// removed when the bench ends, however it ends).
std::vector<RgbdFrame> bench_frames(const BenchPotatoOptions& o, std::optional<io::TempDirectory>& scratch) {
  if (o.frames < 0) throw Error("--frames", "must be at least 0 (0: every frame)");
  if (!o.data.empty()) return with_colour(read_bench_frames(o.data, o.frames), o.data);
  sim::PotatoSimConfig cfg;
  apply_config(cfg, ConfigMap{{"scene", o.scene}}, "--scene");
  cfg.validate("--scene");
  scratch.emplace(std::filesystem::temp_directory_path() / "cropsight-bench-potato");
  const std::filesystem::path seq = scratch->path() / "sequence";
  const int n = o.frames > 0 ? o.frames : 40;
  Progress progress("simulate potato", n, o.quiet || o.common.json);
  sim::simulate_potato_sequence(cfg, o.seed, n, seq, false, [&](int done, int) { progress.update(done); });
  progress.finish();
  return with_colour(read_bench_frames(seq.string(), 0), seq.string());
}

nlohmann::json timing_json(const PipelineTiming& t, const PipelineTiming& baseline) {
  nlohmann::json stages = nlohmann::json::object();
  for (const auto& s : t.stage_ms_per_frame()) stages[s.name] = json_number(s.ms);
  return {{"ms_per_frame", json_number(t.ms_per_frame())},
          {"fps", json_number(t.fps())},
          {"cpu_ms_per_frame", json_number(t.cpu_ms_per_frame())},
          {"cpu_fps", json_number(t.cpu_fps())},
          {"frames_with_target", t.clusters},
          {"stages_ms", stages},
          {"ratio_to_baseline", json_number(pipeline::time_ratio(t, baseline).cpu)}};
}

void run(const BenchPotatoOptions& o) {
  if (o.repeat < 1) throw Error("--repeat", "must be at least 1");
  // Single-threaded: the target is one core; no stage may use TBB's pool (the library's
  // timing also runs OpenCV on one thread).
  tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  // Every preset is built before the frames are made, so that a bad name or key fails first.
  std::vector<std::pair<std::string, std::unique_ptr<pp::Pipeline>>> presets;
  for (const auto& name : split_list(o.presets, "--presets"))
    presets.emplace_back(name, pp::make_pipeline({.preset = name, .sets = o.common.sets}));
  std::optional<io::TempDirectory> scratch;
  const std::vector<RgbdFrame> frames = bench_frames(o, scratch);
  const PipelineTiming baseline = pp::time_lab_conversion(frames, o.repeat);
  nlohmann::json out{
      {"data", o.data.empty() ? "simulated (scene " + o.scene + ", seed " + std::to_string(o.seed) + ")" : o.data},
      {"frames", frames.size()},
      {"repeat", o.repeat},
      {"threads", 1},
      {"width", frames[0].color.width},
      {"height", frames[0].color.height},
      {"baseline_lab_conversion_ms", json_number(baseline.cpu_ms_per_frame())}};
  if (!o.common.json)
    std::printf("%zu frames x %d, %dx%d, single-threaded; baseline RGB->Lab %.3f ms/frame (CPU)\n", frames.size(),
                o.repeat, frames[0].color.width, frames[0].color.height, baseline.cpu_ms_per_frame());
  for (auto& [name, pipeline] : presets) {
    const PipelineTiming t = pp::time_potato_pipeline(*pipeline, frames, o.repeat);
    out["presets"][name] = timing_json(t, baseline);
    if (o.common.json) continue;
    std::printf("  %-14s %7.2f ms/frame %6.1f fps (CPU %.2f ms, %.1f fps, %.1fx baseline)  [", name.c_str(),
                t.ms_per_frame(), t.fps(), t.cpu_ms_per_frame(), t.cpu_fps(), pipeline::time_ratio(t, baseline).cpu);
    for (const auto& s : t.stage_ms_per_frame()) std::printf(" %s %.2f", s.name.c_str(), s.ms);
    std::printf(" ]  target in %ld of %ld frames\n", t.clusters, t.frames);
  }
  if (o.common.json) print_json(out);
}
}  // namespace bench_potato_cmd

void add_bench_potato(CLI::App& bench) {
  using namespace bench_potato_cmd;
  auto o = std::make_shared<BenchPotatoOptions>();
  auto* cmd = bench.add_subcommand("potato", "Time the potato loop per stage (single-threaded) against a baseline");
  cmd->add_option("--data", o->data, "RGB-D sequence (default: one simulated approach in a temporary folder)");
  cmd->add_option("--presets", o->presets, "Comma-separated presets to time (default potato); --set applies to each");
  cmd->add_option("--frames", o->frames, "Frames: the first N of --data, or N simulated (default: all / 40)");
  cmd->add_option("--repeat", o->repeat, "Passes over the frames, each a fresh approach (default 3)");
  cmd->add_option("--scene", o->scene, "Simulated scene without --data: sheet, room or chamber")
      ->check(CLI::IsMember({"sheet", "room", "chamber"}));
  cmd->add_option("--seed", o->seed, "Seed of the simulated approach (default 1)");
  cmd->add_flag("--quiet", o->quiet, "no progress line");
  cmd->add_option("--set", o->common.sets, "key=value applied over every preset (repeatable)");
  add_json_flag(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
