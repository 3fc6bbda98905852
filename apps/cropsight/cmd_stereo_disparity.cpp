// cropsight stereo disparity: dense disparity of one pair (optionally rectified with a
// calibration first) with our matcher, plain OpenCV SGBM or the paper's SAD / SSD baselines.
#include <cstdio>
#include <filesystem>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/report/render.hpp"
#include "cropsight/stereo/calibration.hpp"
#include "cropsight/stereo/disparity.hpp"
#include "cropsight/stereo/rectification.hpp"
#include "cropsight/stereo/stereo_io.hpp"
#include "seedling_cli.hpp"

namespace cropsight::cli {

namespace stereo_disparity_cmd {

struct DisparityOptions {
  CommonOptions common;
  std::string left, right, calib, out, preview, method = "sgm";
  int max_disp = 128, window = 55;
  bool force = false;
};

void run_disparity(const DisparityOptions& o) {
  // Options and the output first, before any image is read or matched.
  if (o.max_disp % 16 != 0 || o.max_disp <= 0 || o.max_disp > stereo::kMaxDisparities)
    throw Error("--max-disp", "must be a multiple of 16 in 16.." + std::to_string(stereo::kMaxDisparities) + ", got " +
                                  std::to_string(o.max_disp));
  if (o.method != "sgm" && o.method != "opencv-sgbm" && o.method != "sad" && o.method != "ssd")
    throw Error("--method", "expected sgm, opencv-sgbm, sad or ssd, got '" + o.method + "'");
  if (o.window < 1 || o.window % 2 == 0 || o.window > stereo::kMaxBlockWindow)
    throw Error("--window",
                "must be odd, 1.." + std::to_string(stereo::kMaxBlockWindow) + ", got " + std::to_string(o.window));
  // The PNG stores disparity x 256 in 16 bits: an 8-bit or lossy format (JPEG) would not hold it.
  stereo::check_image_output(o.out, "--out", true);
  io::OutputPolicy policy = output_policy("stereo disparity", o.force, {o.left, o.right, o.calib, o.common.config});
  io::check_output_file(o.out, policy);
  policy.inputs.emplace_back(o.out);
  if (!o.preview.empty()) io::check_output_file(o.preview, policy);
  stereo::DisparityConfig cfg;
  cfg.num_disparities = o.max_disp;
  apply_checked_config(cfg, o.common, "", [](const stereo::DisparityConfig& c, const std::string& where) {
    stereo::validate_disparity_config(c, where);
  });
  auto [l, r] = stereo::read_color_pair(o.left, o.right);
  // A search range wider than the image matches nothing more and only costs memory and time.
  const int nd = o.method == "sgm" ? cfg.num_disparities : o.max_disp;
  if (nd > l.width)
    throw Error(o.method == "sgm" && nd != o.max_disp ? "--set" : "--max-disp",
                "'num_disparities' " + std::to_string(nd) + " exceeds the width of " + o.left + " (" +
                    std::to_string(l.width) + " px)");
  if (!o.calib.empty()) {
    const auto calib = stereo::load_calibration(o.calib);
    if (!stereo::is_rectified(calib))
      std::tie(l, r) = stereo::StereoRectifier(calib).rectify(l, r, o.left);
    else if (l.width != calib.width || l.height != calib.height)
      throw Error(o.left, "image size differs from the calibration " + o.calib);
  }
  StageTimer timer;
  stereo::DisparityImage d;
  {
    auto s = timer.scope("disparity");
    if (o.method == "sgm")
      d = stereo::compute_disparity(l, r, cfg, o.left);
    else if (o.method == "opencv-sgbm")
      d = stereo::opencv_sgbm_disparity(l, r, o.max_disp, 3, o.left);
    else
      d = stereo::block_matching(stereo::grey_levels(l), stereo::grey_levels(r), o.max_disp, o.window,
                                 o.method == "sad" ? stereo::BlockCost::kSad : stereo::BlockCost::kSsd, o.left);
  }
  const double ms = timer.total_ms();
  stereo::write_disparity_png(o.out, d, 256.0);
  if (!o.preview.empty()) io::write_color(o.preview, report::disparity_colormap(stereo::scaled_disparity(d, 256.0)));
  const double valid_pct = stereo::valid_percent(d);
  if (o.common.json) {
    print_json({{"out", o.out},
                {"method", o.method},
                {"ms", json_number(ms)},
                {"valid_percent", json_number(valid_pct)},
                {"scale", 256}});
  } else {
    std::printf("%s disparity in %.1f ms, %.1f%% of pixels valid -> %s (16-bit, disparity x 256)\n", o.method.c_str(),
                ms, valid_pct, o.out.c_str());
  }
}

}  // namespace stereo_disparity_cmd

void add_stereo_disparity(CLI::App& parent) {
  using namespace stereo_disparity_cmd;
  auto dopt = std::make_shared<DisparityOptions>();
  auto* dis = parent.add_subcommand("disparity", "Dense disparity of a stereo pair");
  dis->add_option("--left", dopt->left, "Left image")->required();
  dis->add_option("--right", dopt->right, "Right image")->required();
  dis->add_option("--calib", dopt->calib, "Calibration YAML: rectify first (Bouguet)");
  dis->add_option("--max-disp", dopt->max_disp,
                  "Disparity search range: multiple of 16, at most the image width and 1024")
      ->capture_default_str();
  dis->add_option("--method", dopt->method, "sgm (ours) | opencv-sgbm | sad | ssd")->capture_default_str();
  dis->add_option("--window", dopt->window, "SAD/SSD window side, odd, 1..255 (paper: 55)")->capture_default_str();
  dis->add_option("--out", dopt->out, "16-bit image (.png, .tif, .tiff, .pgm), disparity x 256, 0 = none")->required();
  dis->add_option("--preview", dopt->preview,
                  "Colour picture of the disparity to look at (.png: near red, far blue, none black)");
  add_force_flag(dis, dopt->force);
  add_json_flag(dis, dopt->common);
  add_config_options(dis, dopt->common);
  dis->callback([dopt] { run_disparity(*dopt); });
}

}  // namespace cropsight::cli
