// cropsight detect broccoli: runs a trained detector over a sequence and writes one JSON line
// per frame (detections.jsonl) and, with --masks, one 16-bit PNG per frame whose pixels hold the
// 1-based detection number (0 = none). Outputs appear atomically: the JSONL is written to a
// temporary name and renamed; masks go to a temporary sibling directory renamed at the end.
//
// Extension point (sizing / tracking, src/measure + src/tracking): add options in
// add_detect_broccoli() and push a DetectHooks entry in run(); each hook sees every frame's
// detections (and may fill Detection::size_m / track_id and extra JSON fields) and is finished
// once after the last frame (e.g. to write --map map.csv).
#include <unistd.h>
#include <cstdio>
#include <filesystem>

#include <algorithm>
#include <chrono>
#include <functional>
#include <system_error>

#include "broccoli_cli.hpp"
#include "broccoli_tracking.hpp"
#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/pipeline/broccoli_detector.hpp"
#include "cropsight/pipeline/broccoli_training.hpp"

namespace cropsight::cli {

namespace fs = std::filesystem;

/// Per-frame and end-of-run callbacks for modules that build on broccoli detections.
struct DetectHooks {
  std::function<void(const RgbdFrame&, const pipeline::BroccoliDetector&, std::vector<Detection>&, nlohmann::json&)>
      frame;
  std::function<void(nlohmann::json& summary)> finish;
};

namespace {
struct DetectOptions {
  CommonOptions common;
  std::string data, model, out, masks;
  bool quiet = false;
  TrackOptions track;  // --track, --map (issue 4)
};

nlohmann::json detection_json(const Detection& d, int id) {
  return {{"id", id},
          {"score", d.score},
          {"centroid", {d.centroid.x(), d.centroid.y(), d.centroid.z()}},
          {"box", {d.box.x, d.box.y, d.box.width, d.box.height}},
          {"points", d.indices.size()}};
}

// The --masks directory, checked before any work: it is replaced as a whole at the end, so it must
// be new, empty, or a previous run's masks (NNNNNN.png files only) — never a folder that holds
// anything else, which the replacement would delete.
fs::path mask_directory(const std::string& masks) {
  if (masks.empty()) return {};
  fs::path dir(masks);
  if (!dir.has_filename()) dir = dir.parent_path();  // "out/masks/"
  std::error_code ec;
  const auto st = fs::status(dir, ec);
  if (!fs::exists(st)) return dir;
  if (!fs::is_directory(st)) throw Error(masks, "exists and is not a directory");
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    const bool mask_file = e.is_regular_file() && name.size() == 10 && name.ends_with(".png") &&
                           std::all_of(name.begin(), name.begin() + 6, [](char c) { return c >= '0' && c <= '9'; });
    if (!mask_file)
      throw Error(masks, "holds '" + name +
                             "', which is not a mask of an earlier run; --masks replaces the whole directory, so "
                             "give a new or empty one");
  }
  if (ec) throw Error(masks, "cannot list the directory: " + ec.message());
  return dir;
}

// Puts the finished directory `tmp` in place of `dir`; the previous `dir` is moved aside first and
// removed only once the new one is in place, so a failure leaves the old masks.
void replace_directory(const fs::path& tmp, const fs::path& dir) {
  std::error_code ec;
  const fs::path old = dir.parent_path() / ("." + dir.filename().string() + ".old-" + std::to_string(::getpid()));
  const bool had_old = fs::exists(dir, ec);
  if (had_old) {
    fs::rename(dir, old, ec);
    if (ec) throw Error(dir.string(), "cannot replace the previous masks: " + ec.message());
  }
  fs::rename(tmp, dir, ec);
  if (ec) {
    std::error_code ec2;
    if (had_old) fs::rename(old, dir, ec2);
    throw Error(dir.string(), "cannot write the masks: " + ec.message());
  }
  if (had_old) fs::remove_all(old, ec);
}

void run(const DetectOptions& o) {
  const auto model = load_broccoli_model(o.model);
  ConfigMap config = o.common.config_map();
  const ConfigMap track_keys = take_tracking_keys(config);  // sizing.* / tracking.* (issue 4)
  const auto cfg = pipeline::config_for_model(*model, config, o.model);
  pipeline::BroccoliDetector detector(cfg);
  detector.set_model(model, o.model);
  io::SequenceReader reader(o.data);
  std::vector<DetectHooks> hooks;  // sizing / tracking hooks are added here (see the file comment)
  if (o.track.track || !o.track.map.empty()) {
    auto tracker =
        std::make_shared<DetectTracking>(o.track, track_keys, o.common.config.empty() ? "--set" : o.common.config);
    hooks.push_back({[tracker](const RgbdFrame& f, const pipeline::BroccoliDetector& d, std::vector<Detection>& dets,
                               nlohmann::json& line) { tracker->frame(f, d, dets, line); },
                     [tracker](nlohmann::json& summary) { tracker->finish(summary); }});
  }

  // Masks: a temporary sibling directory, renamed over --masks at the end.
  const fs::path masks_dir = mask_directory(o.masks);
  fs::path mask_tmp;
  if (!o.masks.empty()) {
    mask_tmp = masks_dir.parent_path() / ("." + masks_dir.filename().string() + ".tmp-" + std::to_string(::getpid()));
    std::error_code ec;
    fs::remove_all(mask_tmp, ec);
    fs::create_directories(mask_tmp, ec);
    if (ec) throw Error(o.masks, "cannot create the mask directory: " + ec.message());
  }
  struct Cleanup {
    fs::path p;
    ~Cleanup() {
      std::error_code ec;
      if (!p.empty()) fs::remove_all(p, ec);
    }
  } cleanup{mask_tmp};

  std::string lines;
  long total = 0;
  double ms = 0;
  Progress progress("detect broccoli: " + o.data, reader.size(), o.quiet || o.common.json);
  for (int i = 0; i < reader.size(); ++i) {
    const RgbdFrame frame = reader.read(i);
    const auto t0 = std::chrono::steady_clock::now();
    detector.process(frame);
    std::vector<Detection> dets = detector.detections();
    ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    nlohmann::json line{{"frame", frame.index}, {"timestamp", frame.timestamp}};
    for (auto& h : hooks)
      if (h.frame) h.frame(frame, detector, dets, line);
    nlohmann::json arr = nlohmann::json::array();
    for (std::size_t k = 0; k < dets.size(); ++k) arr.push_back(detection_json(dets[k], int(k) + 1));
    line["detections"] = std::move(arr);
    lines += line.dump() + "\n";
    total += long(dets.size());
    if (!mask_tmp.empty()) {
      LabelImage mask(frame.depth.width, frame.depth.height, 0);
      for (std::size_t k = 0; k < dets.size(); ++k)
        for (int idx : dets[k].indices) mask.data[std::size_t(idx)] = std::uint16_t(k + 1);
      io::write_u16(mask_tmp / io::frame_file_name(frame.index), mask);
    }
    progress.update(i + 1);
  }
  progress.finish();
  nlohmann::json summary{{"data", o.data},
                         {"model", o.model},
                         {"out", o.out},
                         {"frames", reader.size()},
                         {"detections", total},
                         {"pipeline", cfg.pipeline},
                         {"fps", ms > 0 ? 1000.0 * reader.size() / ms : 0.0}};
  for (auto& h : hooks)
    if (h.finish) h.finish(summary);
  io::write_file_atomic(o.out, lines);
  if (!mask_tmp.empty()) {
    replace_directory(mask_tmp, masks_dir);
    cleanup.p.clear();
    summary["masks"] = o.masks;
  }
  if (o.common.json) {
    print_json(summary);
  } else {
    std::printf("%d frames, %ld detections (%.1f fps pipeline only); wrote %s%s%s\n", reader.size(), total,
                summary["fps"].get<double>(), o.out.c_str(), o.masks.empty() ? "" : " and masks in ", o.masks.c_str());
  }
}
}  // namespace

void add_detect_broccoli(CLI::App& detect) {
  auto o = std::make_shared<DetectOptions>();
  auto* cmd = detect.add_subcommand("broccoli", "Detect broccoli heads in a sequence with a trained model");
  cmd->add_option("--data", o->data, "Sequence directory")->required();
  cmd->add_option("--model", o->model, "Model file (cropsight train broccoli)")->required();
  cmd->add_option("--out", o->out, "Detections, one JSON line per frame")->required();
  cmd->add_option("--masks", o->masks, "Directory for 16-bit detection-number PNGs (optional)");
  cmd->add_flag("--quiet", o->quiet, "No progress lines");
  add_track_options(cmd, o->track, /*detect=*/true);
  add_config_options(cmd, o->common);
  add_json_flag(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
