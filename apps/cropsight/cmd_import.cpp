// cropsight import: a real recording (folders of 16-bit depth PNGs + colour, or organised PCDs,
// with a camera.yaml) becomes a sequence that detect broccoli reads (io/recording_import.hpp).
#include <iostream>

#include "bag_cli.hpp"
#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/recording_import.hpp"
#include "import_labels_cli.hpp"

namespace cropsight::cli {

namespace import_cmd {
struct ImportCliOptions {
  io::ImportOptions io;
  bool json = false;
  std::string bag;
  BagTopicOptions topics;
  LabelImportOptions labels;  // --coco / --labelme / --cvat
};

// A ROS bag: depth, camera_info and colour topics.
void run_bag(const ImportCliOptions& o) {
  if (!o.io.depth_dir.empty() || !o.io.pcd_dir.empty() || !o.io.camera_yaml.empty() || !o.io.timestamps.empty())
    throw Error("--data",
                "reads depth and camera info from the bag: leave out --depth, --pcd, --camera and --timestamps");
  const BagImportResult r = import_bag(o.bag, o.io.out.string(), o.topics, o.io.overwrite, o.io.poses.string(),
                                       o.io.pose_tolerance_s, o.io.color_camera.string(), o.io.extrinsics.string());
  if (o.json) {
    print_json({{"out", o.io.out.string()},
                {"frames", r.frames},
                {"color", r.color},
                {"unmatched_color", r.unmatched_color},
                {"skipped_without_color", r.skipped_without_color},
                {"poses", r.poses_format}});
  } else {
    std::cout << "wrote " << o.io.out.string() << ": " << r.frames << " frames" << (r.color ? " with colour" : "")
              << (r.unmatched_color ? ", " + std::to_string(r.unmatched_color) + " colour images without depth" : "")
              << (r.skipped_without_color
                      ? ", " + std::to_string(r.skipped_without_color) + " depth frames without colour skipped"
                      : "")
              << (r.poses_format.empty() ? "" : ", poses (" + r.poses_format + ")") << "\n";
  }
}

void run_import(const ImportCliOptions& o) {
  if (o.labels.given()) {
    if (!o.io.depth_dir.empty() || !o.io.pcd_dir.empty() || !o.io.camera_yaml.empty())
      throw Error("--coco/--labelme/--cvat",
                  "import labels onto a sequence (--data SEQ), not with --depth/--pcd/--camera");
    return run_label_import(o.labels, o.bag, o.io.out.string(), o.io.overwrite, o.json);
  }
  if (!o.bag.empty()) return run_bag(o);
  if (o.io.camera_yaml.empty()) throw Error("--camera", "is required (or give --bag)");
  const io::ImportSummary s = io::import_recording(o.io);
  if (o.json) {
    print_json({{"out", o.io.out.string()},
                {"frames", s.frames},
                {"color", s.color},
                {"color_registered", s.color_registered},
                {"labels", s.labels},
                {"timestamps_from_names", s.timestamps_from_names},
                {"timestamps", s.time_source},
                {"poses", s.poses_format}});
  } else {
    std::cout << "wrote " << o.io.out.string() << ": " << s.frames << " frames"
              << (s.color ? (s.color_registered ? " with colour registered to depth" : " with colour") : "")
              << (s.labels ? ", labels" : "") << (s.timestamps_from_names ? ", timestamps from the file names" : "")
              << (s.time_source == "csv" ? ", timestamps from " + o.io.timestamps.string() : "")
              << (s.poses_format.empty() ? "" : ", poses (" + s.poses_format + ")") << "\n";
  }
}
}  // namespace import_cmd

void add_import(CLI::App& app) {
  using namespace import_cmd;
  auto o = std::make_shared<ImportCliOptions>();
  auto* cmd = app.add_subcommand(
      "import", "Turn a recording (16-bit depth PNGs [+ colour] or organised PCDs, camera.yaml) into a sequence");
  cmd->add_option("--depth", o->io.depth_dir, "Folder of 16-bit depth PNGs (Kinect v2 / RealSense recorder layouts)");
  cmd->add_option("--color", o->io.color_dir, "Folder of 8-bit colour PNGs or JPEGs (optional)");
  cmd->add_option("--pcd", o->io.pcd_dir, "Folder of organised .pcd files instead of --depth (metres)");
  cmd->add_option("--camera", o->io.camera_yaml, "Depth intrinsics: camera.yaml or a ROS camera_info YAML");
  cmd->add_option("--color-camera", o->io.color_camera, "Colour intrinsics (same formats): registers colour to depth");
  cmd->add_option("--extrinsics", o->io.extrinsics, "Depth-to-colour transform YAML (docs/formats.md)");
  cmd->add_option("--depth-scale", o->io.depth_scale, "Metres per depth unit (default: the camera file's; 0.001)");
  cmd->add_option("--poses", o->io.poses, "Camera poses joined by time: CSV (timestamp,x,y,z) or TUM");
  cmd->add_option("--pose-tolerance", o->io.pose_tolerance_s, "Seconds a frame's pose may lie from it")
      ->capture_default_str();
  cmd->add_option("--data", o->bag,
                  "A ROS bag instead (.bag: depth 16UC1/32FC1, camera_info, colour; no master needed), or with "
                  "--coco/--labelme/--cvat the sequence the labels were drawn on");
  add_deprecated_option(cmd, "--bag", o->bag, "--data");
  add_bag_topic_options(cmd, o->topics);
  cmd->add_option("--out", o->io.out, "New sequence folder to write")->required();
  cmd->add_option("--timestamps", o->io.timestamps, "CSV of frame (the names' number), timestamp (s)");
  cmd->add_option("--fps", o->io.fps, "Frame rate for frame-numbered files (timestamps = index / fps; default 0)");
  add_label_import_options(cmd, o->labels);
  add_force_flag(cmd, o->io.overwrite);
  cmd->add_flag("--json", o->json, "Print a JSON summary");
  cmd->callback([o] { run_import(*o); });
}

}  // namespace cropsight::cli
