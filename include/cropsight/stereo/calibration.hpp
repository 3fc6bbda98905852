#pragma once
// Stereo calibration from checkerboard views (OpenCV calibrateCamera + stereoCalibrate) and its
// YAML file. Frames: left camera frame x right, y down, z forward; (R, T) map left-camera
// coordinates into the right camera (x_r = R x_l + T), T in metres, so the baseline is |T|.
#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "cropsight/core/image.hpp"

namespace cropsight::stereo {

struct StereoCalibration {
  int width = 0, height = 0;                                                           ///< image size, pixels
  Eigen::Matrix3d K1 = Eigen::Matrix3d::Identity(), K2 = Eigen::Matrix3d::Identity();  ///< intrinsics
  std::vector<double> D1, D2;  ///< distortion, OpenCV order (k1 k2 p1 p2 k3)
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d T = Eigen::Vector3d::Zero();                               ///< m
  Eigen::Matrix3d E = Eigen::Matrix3d::Zero(), F = Eigen::Matrix3d::Zero();  ///< essential / fundamental
  double rms = 0;  ///< px; RMS reprojection error of the stereo fit
  int views = 0;   ///< checkerboard pairs used

  double baseline() const { return T.norm(); }
};

/// OpenCV's corner finder needs at least 3 inner corners each way; 100 is far beyond any printed board.
inline constexpr int kMinBoardCorners = 3, kMaxBoardCorners = 100;
/// Largest checkerboard square accepted, metres (a 1 m square is already an unusual board).
inline constexpr double kMaxSquareSize = 1.0;

struct Checkerboard {
  int cols = 9;               ///< inner corners per row
  int rows = 6;               ///< inner corners per column
  double square_size = 0.03;  ///< m
  /// Corner positions on the board plane (z = 0), row-major, metres.
  std::vector<Eigen::Vector3f> object_points() const;
  /// Throws Error(where, ...) unless kMinBoardCorners <= cols, rows <= kMaxBoardCorners and
  /// 0 < square_size <= kMaxSquareSize (finite).
  void validate(const std::string& where) const;
};

struct CalibrationConfig {
  int min_views = 4;   ///< checkerboard pairs needed (both images detected)
  bool fix_k3 = true;  ///< estimate k1 k2 p1 p2 only (wide lenses: set false)

  template <class V>
  void visit(V& v) {
    v("min_views", min_views, "checkerboard pairs with the board found in both images needed to calibrate");
    v("fix_k3", fix_k3, "keep the 6th-order radial term k3 at zero");
  }
};

/// Calibrates from corner lists (one entry per view, corners in Checkerboard::object_points()
/// order, pixels). Throws Error(where, ...) when fewer than cfg.min_views views are given, when the
/// lists disagree in length, or when a view has the wrong number of corners.
StereoCalibration calibrate_stereo(const std::vector<std::vector<Eigen::Vector2f>>& left_corners,
                                   const std::vector<std::vector<Eigen::Vector2f>>& right_corners,
                                   const Checkerboard& board, int width, int height, const CalibrationConfig& cfg,
                                   const std::string& where = "calibration");

/// Finds the checkerboard's inner corners (sub-pixel refined); false when not found.
bool find_corners(const GrayImage& image, const Checkerboard& board, std::vector<Eigen::Vector2f>& corners);

/// Calibrates from the image pairs DIR/left_*.png + DIR/right_*.png (matched by sorted name).
/// Pairs where the board is not found in both images are skipped. Throws Error(dir, ...) when the
/// folder has no pairs, the images differ in size, or fewer than cfg.min_views pairs remain.
StereoCalibration calibrate_stereo_folder(const std::filesystem::path& dir, const Checkerboard& board,
                                          const CalibrationConfig& cfg);

/// YAML with keys image_width, image_height, K1, D1, K2, D2, R, T, E, F (row-major lists), rms,
/// views. Written atomically.
void save_calibration(const std::filesystem::path& path, const StereoCalibration& calib);
/// Throws Error(path, "missing key 'K1'") and the like for absent, malformed or unknown keys (a
/// misspelt key must not pass silently, as in camera.yaml).
StereoCalibration load_calibration(const std::filesystem::path& path);

}  // namespace cropsight::stereo
