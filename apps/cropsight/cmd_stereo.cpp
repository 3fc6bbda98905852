// cropsight stereo calibrate | disparity: checkerboard calibration of a stereo pair here,
// dense disparity of one pair in cmd_stereo_disparity.cpp.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/config.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/stereo/calibration.hpp"
#include "seedling_cli.hpp"

namespace cropsight::cli {

namespace stereo_cmd {

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
  bool force = false;
};

void run_calibrate(const CalibrateOptions& o) {
  const auto board = parse_board(o.board, o.square_mm);
  io::check_output_file(o.out, output_policy("stereo calibrate", o.force, {o.images, o.common.config}));
  stereo::CalibrationConfig cfg;
  apply_checked_config(cfg, o.common, "", validate_calibration_config);
  const auto calib = stereo::calibrate_stereo_folder(o.images, board, cfg);
  stereo::save_calibration(o.out, calib);
  if (o.common.json) {
    print_json({{"out", o.out},
                {"views", calib.views},
                {"rms_px", json_number(calib.rms)},
                {"baseline_m", json_number(calib.baseline())},
                {"fx_left", json_number(calib.K1(0, 0))},
                {"fx_right", json_number(calib.K2(0, 0))}});
  } else {
    std::printf("calibrated from %d views: rms %.3f px, baseline %.2f mm, fx %.1f / %.1f px -> %s\n", calib.views,
                calib.rms, calib.baseline() * 1000, calib.K1(0, 0), calib.K2(0, 0), o.out.c_str());
  }
}

}  // namespace stereo_cmd

void add_stereo(CLI::App& app) {
  using namespace stereo_cmd;
  auto* stereo = app.add_subcommand("stereo", "Stereo calibration and disparity (broccoli seedlings)");
  stereo->require_subcommand(1);

  auto co = std::make_shared<CalibrateOptions>();
  auto* cal = stereo->add_subcommand("calibrate", "Calibrate a stereo pair from checkerboard images");
  cal->add_option("--images", co->images, "Folder with left_*.png / right_*.png checkerboard pairs")->required();
  cal->add_option("--board", co->board, "Inner corners COLSxROWS, 3..100 each")->capture_default_str();
  cal->add_option("--square-mm", co->square_mm, "Checkerboard square side, mm (0 < s <= 1000)")->capture_default_str();
  cal->add_option("--out", co->out, "Calibration YAML to write")->required();
  add_force_flag(cal, co->force);
  add_json_flag(cal, co->common);
  add_config_options(cal, co->common);
  cal->callback([co] { run_calibrate(*co); });

  add_stereo_disparity(*stereo);
}

}  // namespace cropsight::cli
