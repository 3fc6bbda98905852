// cropsight stereo calibrate | disparity (issue 5): checkerboard calibration of a stereo pair and
// dense disparity of one pair (optionally rectified with a calibration first).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/config.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/stereo/calibration.hpp"
#include "cropsight/stereo/disparity.hpp"
#include "cropsight/stereo/rectification.hpp"
#include "cropsight/stereo/stereo_io.hpp"
#include "seedling_cli.hpp"

namespace cropsight::cli {

namespace {

stereo::Checkerboard parse_board(const std::string& text, double square_mm) {
  stereo::Checkerboard b;
  char x = 0;
  std::istringstream in(text);
  if (!(in >> b.cols >> x >> b.rows) || (x != 'x' && x != 'X') || !(in >> std::ws).eof())
    throw Error("--board", "expected COLSxROWS inner corners such as 9x6, got '" + text + "'");
  // OpenCV's corner finder asserts on boards smaller than 3x3 (kMinBoardCorners).
  if (b.cols < stereo::kMinBoardCorners || b.rows < stereo::kMinBoardCorners || b.cols > stereo::kMaxBoardCorners ||
      b.rows > stereo::kMaxBoardCorners)
    throw Error("--board", "needs " + std::to_string(stereo::kMinBoardCorners) + ".." +
                               std::to_string(stereo::kMaxBoardCorners) + " inner corners each way, got '" + text +
                               "'");
  // inf / 1e300 would reach calibrateCamera as non-finite object points.
  if (!(std::isfinite(square_mm) && square_mm > 0 && square_mm <= stereo::kMaxSquareSize * 1000))
    throw Error("--square-mm", "must be a finite number in (0, " + std::to_string(int(stereo::kMaxSquareSize * 1000)) +
                                   "] mm, got " + cropsight::detail::format_value(square_mm));
  b.square_size = square_mm / 1000.0;
  return b;
}

void validate_calibration_config(const stereo::CalibrationConfig& c, const std::string& where) {
  if (c.min_views < 1 || c.min_views > 10000)
    throw Error(where, "'min_views' must be in 1..10000, got " + std::to_string(c.min_views));
}

struct CalibrateOptions {
  CommonOptions common;
  std::string images, board = "9x6", out;
  double square_mm = 30;
};

void run_calibrate(const CalibrateOptions& o) {
  const auto board = parse_board(o.board, o.square_mm);
  if (std::filesystem::is_directory(o.out)) throw Error(o.out, "is a folder; --out needs a file name such as rig.yaml");
  stereo::CalibrationConfig cfg;
  apply_checked_config(cfg, o.common, "", validate_calibration_config);
  const auto calib = stereo::calibrate_stereo_folder(o.images, board, cfg);
  stereo::save_calibration(o.out, calib);
  if (o.common.json) {
    print_json({{"out", o.out},
                {"views", calib.views},
                {"rms_px", calib.rms},
                {"baseline_m", calib.baseline()},
                {"fx_left", calib.K1(0, 0)},
                {"fx_right", calib.K2(0, 0)}});
  } else {
    std::printf("calibrated from %d views: rms %.3f px, baseline %.2f mm, fx %.1f / %.1f px -> %s\n", calib.views,
                calib.rms, calib.baseline() * 1000, calib.K1(0, 0), calib.K2(0, 0), o.out.c_str());
  }
}

struct DisparityOptions {
  CommonOptions common;
  std::string left, right, calib, out, method = "sgm";
  int max_disp = 128, window = 55;
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
  const auto t0 = std::chrono::steady_clock::now();
  stereo::DisparityImage d;
  if (o.method == "sgm") {
    d = stereo::compute_disparity(l, r, cfg, o.left);
  } else if (o.method == "opencv-sgbm") {
    d = stereo::opencv_sgbm_disparity(l, r, o.max_disp, 3, o.left);
  } else if (o.method == "sad" || o.method == "ssd") {
    GrayImage gl(l.width, l.height), gr(r.width, r.height);
    for (std::size_t i = 0; i < l.size(); ++i) {
      gl.data[i] = std::uint8_t((l.data[i].r * 77 + l.data[i].g * 150 + l.data[i].b * 29) >> 8);
      gr.data[i] = std::uint8_t((r.data[i].r * 77 + r.data[i].g * 150 + r.data[i].b * 29) >> 8);
    }
    d = stereo::block_matching(gl, gr, o.max_disp, o.window,
                               o.method == "sad" ? stereo::BlockCost::kSad : stereo::BlockCost::kSsd, o.left);
  } else {
    throw Error("--method", "expected sgm, opencv-sgbm, sad or ssd, got '" + o.method + "'");
  }
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  stereo::write_disparity_png(o.out, d, 256.0);
  long valid = 0;
  for (float v : d.data) valid += std::isfinite(v);
  const double valid_pct = 100.0 * double(valid) / double(std::max<std::size_t>(1, d.size()));
  if (o.common.json) {
    print_json({{"out", o.out}, {"method", o.method}, {"ms", ms}, {"valid_percent", valid_pct}, {"scale", 256}});
  } else {
    std::printf("%s disparity in %.1f ms, %.1f%% of pixels valid -> %s (16-bit, disparity x 256)\n", o.method.c_str(),
                ms, valid_pct, o.out.c_str());
  }
}

}  // namespace

void add_stereo(CLI::App& app) {
  auto* stereo = app.add_subcommand("stereo", "Stereo calibration and disparity (broccoli seedlings, issue 5)");
  stereo->require_subcommand(1);

  auto co = std::make_shared<CalibrateOptions>();
  auto* cal = stereo->add_subcommand("calibrate", "Calibrate a stereo pair from checkerboard images");
  cal->add_option("--images", co->images, "Folder with left_*.png / right_*.png checkerboard pairs")->required();
  cal->add_option("--board", co->board, "Inner corners COLSxROWS, 3..100 each")->capture_default_str();
  cal->add_option("--square-mm", co->square_mm, "Checkerboard square side, mm (0 < s <= 1000)")->capture_default_str();
  cal->add_option("--out", co->out, "Calibration YAML to write")->required();
  add_json_flag(cal, co->common);
  add_config_options(cal, co->common);
  cal->callback([co] { run_calibrate(*co); });

  auto dopt = std::make_shared<DisparityOptions>();
  auto* dis = stereo->add_subcommand("disparity", "Dense disparity of a stereo pair");
  dis->add_option("--left", dopt->left, "Left image")->required();
  dis->add_option("--right", dopt->right, "Right image")->required();
  dis->add_option("--calib", dopt->calib, "Calibration YAML: rectify first (Bouguet)");
  dis->add_option("--max-disp", dopt->max_disp,
                  "Disparity search range: multiple of 16, at most the image width and 1024")
      ->capture_default_str();
  dis->add_option("--method", dopt->method, "sgm (ours) | opencv-sgbm | sad | ssd")->capture_default_str();
  dis->add_option("--window", dopt->window, "SAD/SSD window side, odd, 1..255 (paper: 55)")->capture_default_str();
  dis->add_option("--out", dopt->out, "16-bit image (.png, .tif, .tiff, .pgm), disparity x 256, 0 = none")->required();
  add_json_flag(dis, dopt->common);
  add_config_options(dis, dopt->common);
  dis->callback([dopt] { run_disparity(*dopt); });
}

}  // namespace cropsight::cli
