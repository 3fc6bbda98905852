// cropsight bench broccoli: times the OES, ORG and FEC detectors and the PCL reference pipeline on
// the same frames in the same process, single-threaded, and prints the per-stage milliseconds, fps
// and each detector's speedup over the PCL reference; --track also times sizing + the temporal
// filter on the OES detections (the extra time per frame of `detect broccoli --track`).
//
// What runs with which settings, and the timing, are the library's (pipeline/broccoli/bench.hpp);
// this file reads the frames (into memory, I/O excluded, without their label images: with labels
// the detector would also copy them, evaluation bookkeeping of ~1 %) and formats the figures.
#include <oneapi/tbb/global_control.h>

#include <cstdio>

#include "broccoli_cli.hpp"
#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/io/config_yaml.hpp"
#include "cropsight/pipeline/broccoli/bench.hpp"

namespace cropsight::cli {

namespace bench_broccoli_cmd {
namespace pb = pipeline::broccoli;

struct BenchOptions {
  CommonOptions common;
  std::string data, pipelines = "oes,org,fec,pcl";
  int frames = 0;
  pb::BenchSpec spec;
};

void print_pipeline(const std::string& name, const pb::BenchedPipeline& p) {
  const pipeline::PipelineTiming& t = p.timing;
  std::printf("  %-14s %8.2f ms/frame %8.1f fps (CPU %.2f ms, %.1f fps)", name.c_str(), t.ms_per_frame(), t.fps(),
              t.cpu_ms_per_frame(), t.cpu_fps());
  if (p.vs_pcl) std::printf("  %6.1fx vs PCL", p.vs_pcl->wall);
  std::printf("   [");
  for (const auto& s : t.stage_ms_per_frame()) std::printf(" %s %.2f", s.name.c_str(), s.ms);
  std::printf(" ]\n");
}

void print_text(const pb::BenchResult& r, const std::vector<RgbdFrame>& frames, int repeat) {
  std::printf("%zu frames x %d, %dx%d, single-threaded\n", frames.size(), repeat, frames[0].depth.width,
              frames[0].depth.height);
  for (const auto& [name, p] : r.detectors) print_pipeline(name, p);
  if (r.pcl_reference) print_pipeline("pcl_reference", *r.pcl_reference);
  if (const auto& t = r.tracking)
    std::printf("  sizing + tracking (OES detections, %.1f per frame): %.3f ms/frame (CPU %.3f ms), %.1f %% of OES\n",
                t->timing.clusters_per_frame(), t->timing.ms_per_frame(), t->timing.cpu_ms_per_frame(),
                100.0 * t->vs_oes.wall);
}

// One timed pipeline, with its speedup over the PCL reference when that ran.
nlohmann::json pipeline_timing_json(const pb::BenchedPipeline& p) {
  const pipeline::PipelineTiming& t = p.timing;
  nlohmann::json j{{"ms_per_frame", t.ms_per_frame()},
                   {"fps", t.fps()},
                   {"cpu_ms_per_frame", t.cpu_ms_per_frame()},
                   {"cpu_fps", t.cpu_fps()},
                   {"clusters_per_frame", t.clusters_per_frame()},
                   {"stages_ms", stages_json(t.stage_ms_per_frame())}};
  if (p.vs_pcl) {
    j["speedup_vs_pcl"] = p.vs_pcl->wall;
    j["cpu_speedup_vs_pcl"] = p.vs_pcl->cpu;
  }
  return j;
}

// Sizing + tracking against the OES detector of the same run, with the sizing keys it ran under.
nlohmann::json tracking_timing_json(const pb::BenchedTracking& t) {
  const auto& sz = t.mapping.sizing;
  return {{"ms_per_frame", t.timing.ms_per_frame()},
          {"cpu_ms_per_frame", t.timing.cpu_ms_per_frame()},
          {"detections_per_frame", t.timing.clusters_per_frame()},
          {"ratio_to_oes", t.vs_oes.wall},
          {"cpu_ratio_to_oes", t.vs_oes.cpu},
          {"sizing",
           {{"estimator", sz.estimator},
            {"compute_hull", sz.compute_hull},
            {"hull_engine", sz.hull_engine},
            {"hull_max_points", sz.hull_max_points}}},
          {"use_poses", t.mapping.tracking.use_poses}};
}

nlohmann::json result_json(const BenchOptions& o, const pb::BenchResult& r, const std::vector<RgbdFrame>& frames) {
  nlohmann::json settings = nlohmann::json::object();
  for (const auto& [name, p] : r.detectors) settings[name] = p.settings;
  nlohmann::json out{{"data", o.data},
                     {"model", o.spec.model},
                     {"frames", frames.size()},
                     {"repeat", o.spec.repeat},
                     {"variety", o.spec.variety},
                     {"threads", 1},
                     {"sor", o.spec.sor},
                     {"settings", settings},
                     {"width", frames[0].depth.width},
                     {"height", frames[0].depth.height}};
  for (const auto& [name, p] : r.detectors) out["pipelines"][name] = pipeline_timing_json(p);
  if (r.pcl_reference) out["pipelines"]["pcl_reference"] = pipeline_timing_json(*r.pcl_reference);
  if (r.tracking) out["tracking"] = tracking_timing_json(*r.tracking);
  return out;
}

void run(const BenchOptions& o) {
  pb::BenchSpec spec = o.spec;
  spec.pipelines = split_list(o.pipelines, "--pipelines");
  spec.preset = o.common.config;
  spec.sets = o.common.sets;
  spec.validate();  // before the frames are read
  // Single-threaded: no stage may use TBB's pool (the paper's numbers are single-threaded too).
  tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  const std::vector<RgbdFrame> frames = read_bench_frames(o.data, o.frames);
  const pb::BenchResult r = pb::bench(spec, frames);
  if (o.common.json)
    print_json(result_json(o, r, frames));
  else
    print_text(r, frames, spec.repeat);
}
}  // namespace bench_broccoli_cmd

void add_bench_broccoli(CLI::App& bench) {
  using namespace bench_broccoli_cmd;
  auto o = std::make_shared<BenchOptions>();
  auto* cmd = bench.add_subcommand("broccoli", "Time OES, ORG, FEC and the PCL reference pipeline");
  cmd->add_option("--data", o->data, "Sequence directory")->required();
  cmd->add_option_function<std::string>(
         "--model", [o](const std::string& v) { o->spec.model = io::find_model(v).string(); },
         "Model with VFH features: a shipped model's name (e.g. broccoli-oes-uk) or a file (train broccoli)")
      ->required();
  cmd->add_option("--frames", o->frames, "Frames to time, the first N (default 0: all)");
  cmd->add_option("--repeat", o->spec.repeat, "Passes over the frames (default 1)");
  cmd->add_option("--variety", o->spec.variety, "Presets to use: uk | spain (default uk)");
  cmd->add_flag("--sor", o->spec.sor, "Run statistical outlier removal in FEC and the PCL reference");
  cmd->add_option("--pipelines", o->pipelines, "Comma-separated subset of oes,org,fec,pcl to time (default all)");
  cmd->add_flag("--track", o->spec.track,
                "Also time sizing + the temporal filter on the OES detections (keys sizing.*, tracking.* of the "
                "OES preset and --set)");
  add_config_options(cmd, o->common);
  add_json_flag(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
