// cropsight export --data SEQ --frame I --out FILE.pcd|.ply: one frame as an organised cloud (width
// x height kept, NaN for no return) with colour and ground-truth labels when the sequence has them;
// --out FILE.bag: the whole sequence as a ROS bag.
#include <cstdio>
#include <memory>

#include "bag_cli.hpp"
#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/core/organized_cloud.hpp"
#include "cropsight/io/cloud_io.hpp"
#include "cropsight/io/sequence.hpp"

namespace cropsight::cli {

namespace export_cmd {
struct ExportOptions {
  CommonOptions common;
  std::string seq, out, bag;
  int frame = -1;
  bool ascii = false, force = false;
  double fps = 30;
  BagTopicOptions topics;
};

// The whole sequence as a ROS bag.
void run_bag(const ExportOptions& o) {
  const BagExportResult r = export_bag(o.seq, o.bag, o.topics, o.fps, o.force);
  if (o.common.json) {
    print_json({{"out", o.bag}, {"frames", r.frames}, {"messages", r.messages}, {"color", r.color}});
  } else {
    std::printf("wrote %s: %d frames, %ld messages%s\n", o.bag.c_str(), r.frames, r.messages,
                r.color ? " (depth, camera_info, colour)" : " (depth, camera_info)");
  }
}

void run(ExportOptions o) {
  if (o.seq.empty()) throw Error("--data", "give the sequence folder to export");
  if (!o.bag.empty()) {  // the deprecated --bag OUT.bag
    if (!o.out.empty()) throw Error("--bag", "give the bag as --out OUT.bag");
    o.out = o.bag;
  }
  if (o.out.empty()) throw Error("--out", "give the file to write: FILE.pcd|.ply (one frame) or FILE.bag");
  io::check_output_file(o.out, output_policy("export", o.force, {o.seq}));  // before anything is read
  if (is_bag_file(o.out)) {
    if (o.frame >= 0) throw Error("--frame", "a bag holds the whole sequence: leave out --frame");
    o.bag = o.out;
    return run_bag(o);
  }
  if (o.frame < 0)
    throw Error("--frame", "give the frame to write to " + o.out + " (or --out FILE.bag for every frame)");
  const io::SequenceReader reader(o.seq);
  const RgbdFrame f = reader.read(o.frame);
  const OrganizedCloud cloud = to_organized_cloud(f);
  io::write_cloud(o.out, cloud, !o.ascii);
  if (o.common.json) {
    print_json({{"out", o.out},
                {"frame", o.frame},
                {"width", cloud.width},
                {"height", cloud.height},
                {"valid_points", cloud.count_valid()},
                {"color", cloud.has_color()},
                {"labels", cloud.has_labels()}});
  } else {
    std::printf("wrote %s: frame %d, organised %d x %d, %zu valid points%s%s\n", o.out.c_str(), o.frame, cloud.width,
                cloud.height, cloud.count_valid(), cloud.has_color() ? ", colour" : "",
                cloud.has_labels() ? ", labels" : "");
  }
}
}  // namespace export_cmd

void add_export(CLI::App& app) {
  using namespace export_cmd;
  auto o = std::make_shared<ExportOptions>();
  auto* cmd = app.add_subcommand(
      "export", "Export one frame as an organised point cloud (.pcd or .ply), or the sequence as a ROS bag");
  cmd->add_option("--data", o->seq, "Sequence folder");
  add_deprecated_positional(cmd, o->seq);
  cmd->add_option("--frame", o->frame, "Frame index (from 0)");
  cmd->add_option("--out", o->out,
                  "Output file: .pcd or .ply (one frame), or .bag (every frame: depth 16UC1, camera_info, rgb8)");
  cmd->add_flag("--ascii", o->ascii, "Write ASCII instead of binary");
  add_deprecated_option(cmd, "--bag", o->bag, "--out FILE.bag");
  cmd->add_option("--fps", o->fps, ".bag: frame rate for sequences without timestamps")->capture_default_str();
  add_force_flag(cmd, o->force);
  add_deprecated_flag(cmd, "--overwrite", o->force, "--force");
  add_bag_topic_options(cmd, o->topics);
  add_json_flag(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
