// cropsight bench broccoli: times the OES, ORG and FEC detectors and the PCL reference pipeline
// (pcl_reference.hpp) on the same frames in the same process, single-threaded, and prints the
// per-stage milliseconds, fps and each detector's speedup over the PCL reference.
//
// Frames are read into memory first (I/O excluded) without their label images (as deployed).
// The model's own pipeline runs with the settings the model records (as `detect` and `eval
// broccoli --model` run it), then --set; the other pipelines use their presets
// configs/broccoli-<pipeline>-<variety>.yaml, then --set. Every pipeline scores its clusters with
// the given model's classifier (for the others, timing only: the model must use VFH features, the
// only feature PCL computes). Statistical outlier removal is off for FEC and the
// PCL reference unless --sor, so that both do the same work as the reference
// (normals + Euclidean clustering + VFH + SVM).
//
// The timing itself is the library's (pipeline/broccoli/timing.hpp); this file picks the
// frames and presets and formats the figures.
//
// --track also times sizing + the temporal filter (tracking::HeadMapper with the OES
// preset's sizing.* / tracking.* keys and --set) on the OES detections of the same frames: per
// frame add_frame + predict_missed, and finish() once per pass, i.e. everything `detect broccoli
// --track` adds to the detector. The detector runs untimed in that loop, so the figure is the
// extra time per frame; `ratio_to_oes` divides it by the OES detector's time of the same run.
#include <oneapi/tbb/global_control.h>

#include <cstdio>
#include <map>
#include <optional>
#include <set>

#include "broccoli_cli.hpp"
#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/config_yaml.hpp"
#include "cropsight/pipeline/broccoli/timing.hpp"

namespace cropsight::cli {

namespace bench_broccoli_cmd {
struct BenchOptions {
  CommonOptions common;
  std::string data, model, variety = "uk";
  int frames = 0;
  int repeat = 1;
  bool sor = false;
  bool track = false;
  std::string pipelines = "oes,org,fec,pcl";
};

using pipeline::PipelineTiming;

std::set<std::string> wanted_pipelines(const BenchOptions& o) {
  std::set<std::string> wanted;
  for (const auto& p : split_list(o.pipelines, "--pipelines")) {
    if (p != "oes" && p != "org" && p != "fec" && p != "pcl")
      throw Error("--pipelines", "unknown pipeline '" + p + "' (oes, org, fec, pcl)");
    wanted.insert(p);
  }
  if (o.track && !wanted.count("oes")) throw Error("--track", "times the OES detections: --pipelines must include oes");
  return wanted;
}

// The variety's preset of `pipe`, then --set: sizing.* / tracking.* are checked here too, so that a
// typo is an error; the detector times with VFH and the bench's outlier setting.
pipeline::broccoli::Config preset_of(const BenchOptions& o, const std::string& pipe) {
  const std::string name = "broccoli-" + pipe + "-" + o.variety;
  pipeline::broccoli::Config cfg;
  apply_config(cfg, io::load_config_map(io::find_preset(name)), name);
  apply_config(cfg, o.common.config_map(), "--set");
  cfg.validate(name);
  cfg.detector.features = "vfh";
  cfg.detector.outliers.enabled = o.sor;
  return cfg;
}

// The model's own pipeline: what the model records, then --set (the bench's outlier setting too).
pipeline::broccoli::Config model_settings(const BenchOptions& o, const learning::Model& model) {
  pipeline::broccoli::Config cfg = pipeline::broccoli::config_for_model(model, o.common.config_map(), o.model, "--set");
  cfg.detector.outliers.enabled = o.sor;
  return cfg;
}

void print_text(const std::map<std::string, PipelineTiming>& timings, const PipelineTiming* tracked,
                const std::vector<RgbdFrame>& frames, int repeat) {
  const auto pcl = timings.find("pcl_reference");
  std::printf("%zu frames x %d, %dx%d, single-threaded\n", frames.size(), repeat, frames[0].depth.width,
              frames[0].depth.height);
  for (const auto& [name, t] : timings) {
    std::printf("  %-14s %8.2f ms/frame %8.1f fps (CPU %.2f ms, %.1f fps)", name.c_str(), t.ms_per_frame(), t.fps(),
                t.cpu_ms_per_frame(), t.cpu_fps());
    if (name != "pcl_reference" && pcl != timings.end())
      std::printf("  %6.1fx vs PCL", pcl->second.ms_per_frame() / t.ms_per_frame());
    std::printf("   [");
    for (const auto& s : t.stages) std::printf(" %s %.2f", s.name.c_str(), s.total_ms / double(t.frames));
    std::printf(" ]\n");
  }
  if (tracked)
    std::printf("  sizing + tracking (OES detections, %.1f per frame): %.3f ms/frame (CPU %.3f ms), %.1f %% of OES\n",
                tracked->clusters_per_frame(), tracked->ms_per_frame(), tracked->cpu_ms_per_frame(),
                100.0 * tracked->ms_per_frame() / timings.at("oes").ms_per_frame());
}

void run(const BenchOptions& o) {
  if (o.repeat < 1) throw Error("--repeat", "must be at least 1");
  if (o.variety != "uk" && o.variety != "spain") throw Error("--variety", "must be uk or spain");
  // Single-threaded: no stage may use TBB's pool (the paper's numbers are single-threaded too).
  tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  const auto model = pipeline::broccoli::load_model(o.model);
  // The first --frames frames in memory, without their label images: with labels the detector
  // would also copy them (evaluation bookkeeping, ~1 %).
  const std::vector<RgbdFrame> frames = read_bench_frames(o.data, o.frames);
  const std::set<std::string> wanted = wanted_pipelines(o);
  std::map<std::string, PipelineTiming> timings;
  std::map<std::string, std::string> settings;  // per pipeline: "model" or the preset it ran with
  std::optional<PipelineTiming> tracked;
  tracking::HeadMapperConfig mapping;  // the OES preset's sizing.* / tracking.* keys, then --set
  for (const auto variant :
       {pipeline::broccoli::Variant::oes, pipeline::broccoli::Variant::org, pipeline::broccoli::Variant::fec}) {
    const std::string pipe = config_name(variant);
    if (!wanted.count(pipe)) continue;
    const bool own = model->info.pipeline == pipe;
    const auto cfg = own ? model_settings(o, *model) : preset_of(o, pipe);
    settings[pipe] = own ? "model" : "preset broccoli-" + pipe + "-" + o.variety;
    pipeline::broccoli::Detector det(cfg.detector);
    det.set_model(pipeline::broccoli::model_for_variant(model, variant, o.model), o.model);
    timings[pipe] = pipeline::broccoli::time_detector(det, frames, o.repeat);
    if (variant == pipeline::broccoli::Variant::oes && o.track) {
      mapping = cfg.mapping();
      tracked = pipeline::broccoli::time_tracking(det, mapping, frames, o.repeat);
    }
  }
  if (wanted.count("pcl")) {
    pipeline::broccoli::PclReferencePipeline pcl(preset_of(o, "fec").detector, model, o.model);
    timings["pcl_reference"] = pipeline::broccoli::time_pcl_reference(pcl, frames, o.repeat);
  }
  nlohmann::json out{{"data", o.data},
                     {"model", o.model},
                     {"frames", frames.size()},
                     {"repeat", o.repeat},
                     {"variety", o.variety},
                     {"threads", 1},
                     {"sor", o.sor},
                     {"settings", settings},
                     {"width", frames[0].depth.width},
                     {"height", frames[0].depth.height}};
  const auto pcl = timings.find("pcl_reference");
  for (const auto& [name, t] : timings)
    out["pipelines"][name] = pipeline_json(t, name != "pcl_reference" && pcl != timings.end() ? &pcl->second : nullptr);
  if (tracked) out["tracking"] = tracking_timing_json(*tracked, timings.at("oes"), mapping);
  if (o.common.json)
    print_json(out);
  else
    print_text(timings, tracked ? &*tracked : nullptr, frames, o.repeat);
}
}  // namespace bench_broccoli_cmd

void add_bench_broccoli(CLI::App& bench) {
  using namespace bench_broccoli_cmd;
  auto o = std::make_shared<BenchOptions>();
  auto* cmd = bench.add_subcommand("broccoli", "Time OES, ORG, FEC and the PCL reference pipeline");
  cmd->add_option("--data", o->data, "Sequence directory")->required();
  cmd->add_option_function<std::string>(
         "--model", [o](const std::string& v) { o->model = io::find_model(v).string(); },
         "Model with VFH features: a shipped model's name (e.g. broccoli-oes-uk) or a file (train broccoli)")
      ->required();
  cmd->add_option("--frames", o->frames, "Frames to time, the first N (default 0: all)");
  cmd->add_option("--repeat", o->repeat, "Passes over the frames (default 1)");
  cmd->add_option("--variety", o->variety, "Presets to use: uk | spain (default uk)");
  cmd->add_flag("--sor", o->sor, "Run statistical outlier removal in FEC and the PCL reference");
  cmd->add_option("--pipelines", o->pipelines, "Comma-separated subset of oes,org,fec,pcl to time (default all)");
  cmd->add_flag("--track", o->track,
                "Also time sizing + the temporal filter on the OES detections (keys sizing.*, tracking.* of the "
                "OES preset and --set)");
  add_config_options(cmd, o->common);
  add_json_flag(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
