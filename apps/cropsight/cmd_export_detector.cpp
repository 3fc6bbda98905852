// cropsight export-detector --model det.pt --out det.onnx: the trained CenterNet as an ONNX graph
// that OpenCV DNN runs without libtorch (include/cropsight/nn/center_onnx.hpp), checked by
// loading it back through OpenCV. A verb of its own, not `export detector`: `export SEQ` takes a
// positional sequence, and main.cpp's check for mistyped sub-commands would read SEQ as one.
#include <cstdio>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/io/config_yaml.hpp"
#include "cropsight/nn/center_net.hpp"
#include "cropsight/nn/center_onnx.hpp"

namespace cropsight::cli {

void add_export_detector(CLI::App& app) {
  struct Options {
    std::string model, out;
    bool force = false;
    CommonOptions common;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("export-detector", "Export a trained detector (.pt) as ONNX for OpenCV DNN");
  cmd->add_option("--model", o->model, "Detector model written by train detector (.pt)")->required();
  cmd->add_option("--out", o->out, "ONNX file to write")->required();
  add_force_flag(cmd, o->force);
  add_json_flag(cmd, o->common);
  cmd->callback([o] {
    io::check_output_file(o->out, output_policy("export-detector", o->force, {o->model}));
    const nn::CenterNet net = nn::CenterNet::load(io::find_model(o->model).string(), 1);
    net.export_onnx(o->out);
    const nn::CenterNetOnnx back(o->out);  // OpenCV loads and runs it
    if (o->common.json)
      print_json({{"out", o->out},
                  {"classes", back.class_names()},
                  {"input_width", back.config().input_width},
                  {"input_height", back.config().input_height}});
    else
      std::printf("wrote %s (OpenCV DNN loads it)\n", o->out.c_str());
  });
}

}  // namespace cropsight::cli
