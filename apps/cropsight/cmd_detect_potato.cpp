// cropsight detect potato: every image of a folder (or one image file, or every colour
// frame of an RGB-D sequence, whose depth then reaches the detector) -> <stem>.txt in the paper's
// format ("potato score x1 y1 x2 y2"), optional overlays with the boxes and each box's length
// axis, one JSON line per image. Detection and orientation are the library's pipeline::potato::Pipeline steps
// 1 and 5; this file parses options and writes the outputs, each output folder whole or not at all
// (temporary folder, then rename).
#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/config_yaml.hpp"
#include "cropsight/io/file_names.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/io/voc.hpp"
#include "cropsight/measure/position.hpp"
#include "cropsight/pipeline/potato/overlay.hpp"
#include "potato_cli.hpp"

namespace cropsight::cli {
namespace detect_potato_cmd {
namespace fs = std::filesystem;

struct Options {
  CommonOptions common;
  std::string images, data, out, overlay, model;
  bool force = false;
};

using io::list_images;  // a folder's images in name order, or the one image file named

// One input image: its name for the outputs, its colour and (sequences) its metric depth.
struct Input {
  std::string stem, name;
  ColorImage color;
  Image<float> depth_m;
};

// The inputs in order, read one at a time (a sequence can be long).
class Inputs {
 public:
  explicit Inputs(const Options& o) {
    if (o.images.empty() == o.data.empty()) throw Error("detect potato", "give exactly one of --images and --data");
    if (!o.images.empty()) files_ = list_images(o.images);
    if (!o.data.empty()) seq_ = std::make_unique<io::SequenceReader>(o.data);
    if (seq_ && seq_->size() == 0) throw Error(o.data, "sequence has no frames");
  }
  int size() const { return seq_ ? seq_->size() : int(files_.size()); }
  Input read(int i) const {
    Input in;
    if (!seq_) {
      in.stem = files_[std::size_t(i)].stem().string();
      in.name = files_[std::size_t(i)].filename().string();
      in.color = io::read_color(files_[std::size_t(i)]);
      return in;
    }
    RgbdFrame f = seq_->read(i);
    if (f.color.empty()) throw Error(seq_->color_path(i).string(), "the potato detector needs colour images");
    in.stem = seq_->color_path(i).stem().string();
    in.name = seq_->color_path(i).filename().string();
    if (!f.depth.empty()) in.depth_m = measure::depth_in_metres(f.depth, f.camera.depth_scale);
    in.color = std::move(f.color);
    return in;
  }

 private:
  std::vector<fs::path> files_;
  std::unique_ptr<io::SequenceReader> seq_;
};

void run(const Options& o) {
  // The outputs first: a bad --out or --overlay costs no model load and reads no image.
  const io::OutputPolicy policy = output_policy("detect potato", o.force, {o.images, o.data, o.model, o.common.config});
  io::OutputFolder out(o.out, policy);
  std::unique_ptr<io::OutputFolder> overlay;
  if (!o.overlay.empty()) {
    io::OutputPolicy beside_out = policy;
    beside_out.inputs.push_back(o.out);  // one folder cannot be both outputs
    overlay = std::make_unique<io::OutputFolder>(o.overlay, beside_out);
  }
  // A bad key or model fails before any image is read; --model: the ONNX backend with this model.
  const auto built = make_potato(o.common, o.model);
  pipeline::potato::Pipeline& pipeline = *built;
  const std::vector<std::string> names = pipeline.detector_class_names();
  const Inputs inputs(o);
  nlohmann::json images = nlohmann::json::array();  // --json: one object at the end
  for (int i = 0; i < inputs.size(); ++i) {
    Input in = inputs.read(i);
    // The axes are drawn on the overlays and printed in the JSON lines; without either, they are
    // not estimated (the detection files hold boxes only).
    const pipeline::potato::ImageResult r = pipeline.detect_image(in.color, in.depth_m, overlay || o.common.json);
    const std::vector<Detection2D>& dets = r.detections;
    const std::vector<std::optional<double>>& angles = r.angles;
    const double ms = r.timer.ms("detect");
    io::write_detection_text(out.path() / (in.stem + ".txt"), dets, names);
    if (overlay) {
      pipeline::potato::draw_detections(in.color, dets, angles);
      io::write_color(overlay->path() / (in.stem + ".png"), in.color);
    }
    if (o.common.json)
      images.push_back({{"image", in.name}, {"detections", detections_json(dets, names, angles)}, {"ms", ms}});
    else
      std::printf("%s: %zu potato%s (%.2f ms)\n", in.name.c_str(), dets.size(), dets.size() == 1 ? "" : "es", ms);
  }
  out.commit("detection folder");
  if (overlay) overlay->commit("overlay folder");
  if (o.common.json) print_json({{"out", o.out}, {"images", std::move(images)}});
}

}  // namespace detect_potato_cmd

void add_detect_potato(CLI::App& detect) {
  using namespace detect_potato_cmd;
  auto o = std::make_shared<Options>();
  auto* cmd = detect.add_subcommand("potato", "Detect potatoes in images or an RGB-D sequence");
  cmd->add_option("--images", o->images, "Folder of .jpg/.png images, or one image");
  cmd->add_option("--data", o->data, "RGB-D sequence folder (docs/formats.md): its depth reaches the detector");
  cmd->add_option("--model", o->model, "ONNX detector to run (sets detector.backend=onnx, detector.onnx.model)");
  cmd->add_option("--out", o->out, "New folder to write <stem>.txt detections into")->required();
  cmd->add_option("--overlay", o->overlay, "New folder to write <stem>.png images with the boxes and axes into");
  add_force_flag(cmd, o->force);
  add_json_flag(cmd, o->common);
  add_config_options(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
