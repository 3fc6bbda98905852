// cropsight detect broccoli: runs the broccoli pipeline of a trained model over a sequence and
// writes one JSON line per frame (detections.jsonl) and, with --masks, one 16-bit PNG per frame
// whose pixels hold the 1-based detection number (0 = none). With --track, every line also carries
// the heads' sizes and track ids and the predicted heads, and --map writes the field map. Outputs
// appear atomically: the JSONL and the map are written to temporary names and renamed; masks go
// to a temporary sibling directory that replaces --masks at the end; --overlay writes one picture
// per frame the same way (report/frame_overlays.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <system_error>

#include "bag_cli.hpp"
#include "broccoli_cli.hpp"
#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/report/frame_overlays.hpp"
#include "cropsight/tracking/field_map_io.hpp"

namespace cropsight::cli {

namespace fs = std::filesystem;

namespace detect_broccoli_cmd {
struct DetectOptions {
  CommonOptions common;
  std::string data, model, out, masks, overlay;
  BagTopicOptions topics;
  bool quiet = false, force = false;
  TrackOptions track;  // --track, --map
};

void write_mask(const fs::path& dir, const RgbdFrame& frame, const std::vector<Detection>& dets) {
  LabelImage mask(frame.depth.width, frame.depth.height, 0);
  for (std::size_t k = 0; k < dets.size(); ++k)
    for (int idx : dets[k].indices) mask.data[std::size_t(idx)] = std::uint16_t(k + 1);
  io::write_u16(dir / io::frame_file_name(frame.index), mask);
}

void run(const DetectOptions& o) {
  if (!o.track.map.empty() && !o.track.track) throw Error("--map", "needs --track");
  // Every output is checked before the model is loaded or a frame read: a two-hour recording
  // must not fail at its end because --out cannot be written.
  io::OutputPolicy policy = output_policy("detect broccoli", o.force, {o.data, o.model, o.common.config});
  io::check_output_file(o.out, policy);
  policy.inputs.emplace_back(o.out);  // the outputs must not overlap each other either
  if (!o.track.map.empty()) {
    io::check_output_file(o.track.map, policy);
    policy.inputs.emplace_back(o.track.map);
  }
  std::optional<io::OutputFolder> masks_out;
  if (!o.masks.empty()) masks_out.emplace(o.masks, policy);
  if (!o.masks.empty()) policy.inputs.emplace_back(o.masks);
  std::optional<io::OutputFolder> overlay_out;
  if (!o.overlay.empty()) overlay_out.emplace(o.overlay, policy);
  const auto built = make_broccoli(o.model, o.common, o.track.track);
  pipeline::broccoli::Pipeline& pipe = *built;
  const Recording recording(o.data, o.topics);
  io::SequenceReader reader(recording.sequence());

  std::string lines;
  long total = 0;
  double ms = 0;
  Progress progress("detect broccoli: " + o.data, reader.size(), o.quiet || o.common.json);
  for (int i = 0; i < reader.size(); ++i) {
    const RgbdFrame frame = reader.read(i);
    const pipeline::broccoli::FrameResult& r = pipe.process(frame);
    ms += r.detect_ms();
    nlohmann::json line{{"frame", frame.index}, {"timestamp", frame.timestamp}};
    if (o.track.track) add_tracking_json(r, pipe.mapper(), line);
    nlohmann::json arr = nlohmann::json::array();
    for (std::size_t k = 0; k < r.detections.size(); ++k) arr.push_back(detection_json(r.detections[k], int(k) + 1));
    line["detections"] = std::move(arr);
    lines += line.dump() + "\n";
    total += long(r.detections.size());
    if (masks_out) write_mask(masks_out->path(), frame, r.detections);
    if (overlay_out)
      io::write_color(overlay_out->path() / io::frame_file_name(frame.index), report::broccoli_frame_overlay(frame, r));
    progress.update(i + 1);
  }
  progress.finish();
  nlohmann::json summary{{"data", o.data},
                         {"model", o.model},
                         {"out", o.out},
                         {"frames", reader.size()},
                         {"detections", total},
                         {"pipeline", config_name(pipe.config().detector.pipeline)},
                         {"fps", ms > 0 ? 1000.0 * reader.size() / ms : 0.0}};
  if (o.track.track) {
    const auto& map = pipe.finish();
    summary["map_heads"] = map.size();
    summary["harvestable"] = std::count_if(map.begin(), map.end(), [](const auto& h) { return h.harvestable; });
    summary["size_estimator"] = pipe.config().sizing.estimator;
    if (!o.track.map.empty()) {
      tracking::write_field_map(o.track.map, map);
      summary["map"] = o.track.map;
    }
  }
  io::write_file_atomic(o.out, lines);
  if (masks_out) {
    masks_out->commit("masks");
    summary["masks"] = o.masks;
  }
  if (overlay_out) {
    overlay_out->commit("overlay folder");
    summary["overlay"] = o.overlay;
  }
  if (o.common.json) {
    print_json(summary);
  } else {
    std::printf("%d frames, %ld detections (%.1f fps pipeline only); wrote %s%s%s\n", reader.size(), total,
                summary["fps"].get<double>(), o.out.c_str(), o.masks.empty() ? "" : " and masks in ", o.masks.c_str());
  }
}
}  // namespace detect_broccoli_cmd

void add_detect_broccoli(CLI::App& detect) {
  using namespace detect_broccoli_cmd;
  auto o = std::make_shared<DetectOptions>();
  auto* cmd = detect.add_subcommand("broccoli", "Detect broccoli heads in a sequence with a trained model");
  add_recording_options(cmd, o->data, o->topics, "Sequence folder");
  add_broccoli_model_option(cmd, o->model);
  cmd->add_option("--out", o->out, "Detections, one JSON line per frame")->required();
  cmd->add_option("--masks", o->masks, "New folder for 16-bit detection-number PNGs (optional)");
  cmd->add_option("--overlay", o->overlay,
                  "New folder for pictures: heads tinted green on colour (or a depth colour map), predicted magenta");
  add_force_flag(cmd, o->force);
  cmd->add_flag("--quiet", o->quiet, "No progress lines");
  add_track_options(cmd, o->track, /*detect=*/true);
  add_config_options(cmd, o->common);
  add_json_flag(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
