#pragma once
// The simulated seedling data set on disk (written by sim::write_seedling_dataset, `cropsight
// simulate seedling`): DIR/rig.yaml, DIR/pair_NNN/{left,right,disparity,mask}.png + truth.json.
// This is the reader of that format; the writer is src/sim/seedling/seedling_dataset.cpp.
#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "cropsight/core/image.hpp"
#include "cropsight/measure/envelope.hpp"
#include "cropsight/stereo/disparity.hpp"
#include "cropsight/stereo/rectification.hpp"

namespace cropsight::pipeline::seedling {

/// Ground truth of one pair: what the evaluator compares a detection with.
struct Truth {
  stereo::DisparityImage disparity;                         ///< px, left view; NaN where nothing was hit
  GrayImage mask;                                           ///< 255 where the left view sees the seedling
  measure::EnvelopeBox envelope;                            ///< of the seedling mesh
  Eigen::Vector3d plane_normal = Eigen::Vector3d::UnitZ();  ///< soil, left camera frame, unit, up
  double plane_d = 0;
};

/// Reads PAIR/disparity.png (16-bit, disparity x 256), PAIR/mask.png (8-bit) and PAIR/truth.json
/// (envelope and plane). Throws Error(file, ...) naming the file and the key for a missing or
/// malformed file, a zero or non-finite envelope, or a plane without a unit normal and finite d.
Truth read_truth(const std::filesystem::path& pair_dir);

/// A data set: its rectified geometry and its pair folders in name order.
struct Dataset {
  std::filesystem::path dir;
  stereo::RectifiedGeometry geometry;
  std::vector<std::filesystem::path> pairs;
};

/// Opens DIR with DIR/rig.yaml (or `calib` when not empty). Throws Error for a missing folder, a
/// calibration that is not an ideal (rectified) rig, or a folder without pair_* folders.
Dataset open_dataset(const std::filesystem::path& dir, const std::filesystem::path& calib = {});

/// The left and right images of a pair folder (stereo::read_color_pair).
std::pair<ColorImage, ColorImage> read_pair(const std::filesystem::path& pair_dir);

}  // namespace cropsight::pipeline::seedling
