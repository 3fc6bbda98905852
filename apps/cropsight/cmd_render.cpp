// cropsight render SEQ --frame I --out FILE.png [--what depth|color|labels]: what a person
// looks at first. depth (default): turbo colour map, near = red, with ground-truth outlines.
#include <cstdio>
#include <memory>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/report/render.hpp"

namespace cropsight::cli {

namespace render_cmd {
struct RenderOptions {
  CommonOptions common;
  std::string seq, out, what = "depth";
  int frame = 0;
  bool no_outlines = false, force = false;
};

void run(const RenderOptions& o) {
  if (o.seq.empty()) throw Error("--data", "give the sequence folder to render");
  io::check_output_file(o.out, output_policy("render", o.force, {o.seq}));
  const io::SequenceReader reader(o.seq);
  const RgbdFrame f = reader.read(o.frame);
  ColorImage img;
  if (o.what == "depth") {
    img = report::depth_colormap(f.depth, f.camera.depth_scale);
  } else if (o.what == "color") {
    if (f.color.empty()) throw Error(o.seq, "sequence has no color/ frames to render");
    img = f.color;
  } else {  // labels (CLI11 checks the choice)
    if (f.labels.empty()) throw Error(o.seq, "sequence has no labels/ frames to render");
    img = report::label_colormap(f.labels);
  }
  const bool outlines = !o.no_outlines && !f.labels.empty() && o.what != "labels";
  if (outlines) report::draw_label_outlines(img, f.labels);
  io::write_color(o.out, img);
  if (o.common.json)
    print_json({{"out", o.out},
                {"frame", o.frame},
                {"what", o.what},
                {"width", img.width},
                {"height", img.height},
                {"outlines", outlines}});
  else
    std::printf("wrote %s: frame %d, %s%s, %d x %d\n", o.out.c_str(), o.frame, o.what.c_str(),
                outlines ? " with ground-truth outlines" : "", img.width, img.height);
}
}  // namespace render_cmd

void add_render(CLI::App& app) {
  using namespace render_cmd;
  auto o = std::make_shared<RenderOptions>();
  auto* cmd = app.add_subcommand("render", "Render a frame as a PNG (depth colour map with ground-truth outlines)");
  cmd->add_option("--data", o->seq, "Sequence folder");
  add_deprecated_positional(cmd, o->seq);
  cmd->add_option("--frame", o->frame, "Frame index (from 0)")->required();
  cmd->add_option("--out", o->out, "Output PNG file")->required();
  add_force_flag(cmd, o->force);
  cmd->add_option("--what", o->what, "depth (default), color or labels")
      ->check(CLI::IsMember({"depth", "color", "labels"}));
  cmd->add_flag("--no-outlines", o->no_outlines, "Do not draw ground-truth outlines");
  add_json_flag(cmd, o->common);
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
