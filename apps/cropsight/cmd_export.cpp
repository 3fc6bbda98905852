// cropsight export SEQ --frame I --out FILE.pcd|.ply: one frame as an organised cloud (width x
// height kept, NaN for no return) with colour and ground-truth labels when the sequence has them.
#include <cstdio>
#include <memory>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/organized_cloud.hpp"
#include "cropsight/io/cloud_io.hpp"
#include "cropsight/io/sequence.hpp"

namespace cropsight::cli {

namespace export_cmd {
struct ExportOptions {
  CommonOptions common;
  std::string seq, out;
  int frame = 0;
  bool ascii = false;
};

void run(const ExportOptions& o) {
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
  auto* cmd = app.add_subcommand("export", "Export one frame as an organised point cloud (.pcd or .ply)");
  cmd->add_option("SEQ", o->seq, "Sequence directory")->required();
  cmd->add_option("--frame", o->frame, "Frame index (from 0)")->required();
  cmd->add_option("--out", o->out, "Output file, .pcd or .ply")->required();
  cmd->add_flag("--ascii", o->ascii, "Write ASCII instead of binary");
  add_json_flag(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
