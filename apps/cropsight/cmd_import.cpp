// cropsight import: a real recording (folders of 16-bit depth PNGs + colour, or organised PCDs,
// with a camera.yaml) becomes a sequence that detect broccoli reads (io/recording_import.hpp).
#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/io/recording_import.hpp"

namespace cropsight::cli {

namespace import_cmd {
struct ImportCliOptions {
  io::ImportOptions io;
  bool json = false;
};

void run_import(const ImportCliOptions& o) {
  const io::ImportSummary s = io::import_recording(o.io);
  if (o.json) {
    print_json({{"out", o.io.out.string()},
                {"frames", s.frames},
                {"color", s.color},
                {"timestamps_from_names", s.timestamps_from_names}});
  } else {
    std::cout << "wrote " << o.io.out.string() << ": " << s.frames << " frames" << (s.color ? " with colour" : "")
              << (s.timestamps_from_names ? ", timestamps from the file names" : "") << "\n";
  }
}
}  // namespace import_cmd

void add_import(CLI::App& app) {
  using namespace import_cmd;
  auto o = std::make_shared<ImportCliOptions>();
  auto* cmd = app.add_subcommand(
      "import", "Turn a recording (16-bit depth PNGs [+ colour] or organised PCDs, camera.yaml) into a sequence");
  cmd->add_option("--depth", o->io.depth_dir, "Folder of 16-bit depth PNGs (Kinect v2 / RealSense recorder layouts)");
  cmd->add_option("--color", o->io.color_dir, "Folder of 8-bit colour PNGs registered to depth (optional)");
  cmd->add_option("--pcd", o->io.pcd_dir, "Folder of organised .pcd files instead of --depth (metres)");
  cmd->add_option("--camera", o->io.camera_yaml, "camera.yaml of the depth camera (docs/formats.md)")->required();
  cmd->add_option("--out", o->io.out, "Output sequence directory")->required();
  cmd->add_option("--fps", o->io.fps, "Frame rate for frame-numbered files (timestamps = index / fps; default 0)");
  cmd->add_flag("--force", o->io.overwrite, "Replace an existing output directory");
  cmd->add_flag("--json", o->json, "Print a JSON summary");
  cmd->callback([o] { run_import(*o); });
}

}  // namespace cropsight::cli
