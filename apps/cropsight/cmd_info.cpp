// cropsight info SEQ [--json]: validates every file and frame of a sequence and prints its
// summary (frames, resolution, mean valid-depth fraction, ground-truth instances, camera).
#include <cstdio>
#include <memory>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/report/sequence_summary.hpp"

namespace cropsight::cli {

namespace info_cmd {
struct InfoOptions {
  CommonOptions common;
  std::string seq;
};

void run(const InfoOptions& o) {
  if (o.seq.empty()) throw Error("--data", "give the sequence folder to describe");
  const io::SequenceReader reader(o.seq);
  const report::SequenceSummary s = report::summarize_sequence(reader);
  const CameraIntrinsics& c = s.info.camera;
  if (o.common.json) {
    nlohmann::json j;
    j["sequence"] = o.seq;
    j["frames"] = s.info.frames;
    j["width"] = c.width;
    j["height"] = c.height;
    j["valid_depth_fraction"] = s.valid_depth_fraction;
    j["depth_range_m"] = {s.depth_min_m, s.depth_max_m};
    j["instances"] = s.instances;
    j["has_color"] = s.info.has_color;
    j["has_labels"] = s.info.has_labels;
    j["has_poses"] = s.info.has_poses;
    j["has_timestamps"] = !reader.timestamps().empty();
    j["duration_s"] = reader.timestamps().empty() ? 0.0 : reader.timestamps().back() - reader.timestamps().front();
    j["has_groundtruth"] = s.info.has_groundtruth;
    if (s.info.has_labels) j["labelled_fraction"] = s.labelled_fraction;
    j["camera"] = {{"fx", c.fx},
                   {"fy", c.fy},
                   {"cx", c.cx},
                   {"cy", c.cy},
                   {"depth_scale", c.depth_scale},
                   {"distortion", c.distortion},
                   {"sensor", c.sensor}};
    j["attributes"] = reader.groundtruth().attributes;
    print_json(j);
    return;
  }
  std::printf("sequence     %s (valid)\n", o.seq.c_str());
  std::printf("frames       %d\n", s.info.frames);
  std::printf("resolution   %d x %d\n", c.width, c.height);
  std::printf("valid depth  %.4f (mean fraction of pixels with a return)\n", s.valid_depth_fraction);
  std::printf("depth range  %.3f .. %.3f m\n", s.depth_min_m, s.depth_max_m);
  std::printf("instances    %d (ground truth)\n", s.instances);
  if (!reader.timestamps().empty())
    std::printf("time         %.3f s (from %s)\n", reader.timestamps().back() - reader.timestamps().front(),
                s.info.has_poses ? "poses.csv" : "timestamps.csv");
  std::printf("channels     depth%s%s%s%s\n", s.info.has_color ? ", colour" : "", s.info.has_labels ? ", labels" : "",
              s.info.has_poses ? ", poses" : "", s.info.has_groundtruth ? ", groundtruth" : "");
  std::printf("camera       fx %.3f fy %.3f cx %.3f cy %.3f depth_scale %g m/unit%s%s\n", c.fx, c.fy, c.cx, c.cy,
              c.depth_scale, c.sensor.empty() ? "" : " sensor ", c.sensor.c_str());
}
}  // namespace info_cmd

void add_info(CLI::App& app) {
  using namespace info_cmd;
  auto o = std::make_shared<InfoOptions>();
  auto* cmd = app.add_subcommand("info", "Validate a sequence and print its summary");
  cmd->add_option("--data", o->seq, "Sequence folder");
  add_deprecated_positional(cmd, o->seq);
  add_json_flag(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
