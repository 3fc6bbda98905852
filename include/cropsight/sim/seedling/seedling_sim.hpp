#pragma once
// Binocular-stereo scenes of transplanted broccoli seedlings: a seedling with 4-6 true
// leaves on textured soil among weeds of similar colour, seen by a side-by-side pinhole rig
// (640x480 per eye, 60 mm baseline, wide field of view) from 0.5-0.8 m (configurable up to 2 m),
// at random tilt and exposure (some over-exposed), with exact ground truth. Checkerboard pairs
// for calibration tests come from the same rig.
//
// Frames: world x, y horizontal, z up, soil at z = 0. Left camera frame x right, y down,
// z forward (metres); the right camera sits at +baseline along the left camera's x axis (already
// rectified: disparity = f * baseline / z). Everything is deterministic per (seed, index).
#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "cropsight/core/image.hpp"
#include "cropsight/measure/envelope.hpp"
#include "cropsight/stereo/calibration.hpp"
#include "cropsight/stereo/rectification.hpp"

namespace cropsight::sim {

/// An ideal stereo rig: both cameras share f, cx, cy; x_right = R x_left + T.
struct StereoRigModel {
  int width = 640, height = 480;
  double f = 320, cx = 319.5, cy = 239.5;  ///< px
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d T{-0.06, 0.0, 0.0};  ///< m; the right camera at +60 mm along x
  double baseline() const { return T.norm(); }
};

/// The rig's calibration (K, zero distortion, R, T, E, F): the simulated views are already
/// rectified, so it is ideal (stereo::is_rectified() holds). Written as DIR/rig.yaml.
stereo::StereoCalibration ideal_calibration(const StereoRigModel& rig);
/// The rig's pinhole model as the rectified geometry the reconstruction needs.
stereo::RectifiedGeometry rectified_geometry(const StereoRigModel& rig);

struct SeedlingSimConfig {
  int width = 640, height = 480;                  ///< px per eye (paper: 640x480)
  double hfov_deg = 90;                           ///< horizontal field of view of the rectified views
  double baseline = 0.06;                         ///< m (paper: 60 mm)
  double distance_min = 0.5;                      ///< m; working distance along the optical axis to the seedling base
  double distance_max = 0.8;                      ///< m (paper: 0.5-2 m overall, seedling sensing 0.5-0.8 m)
  double tilt_max_deg = 20;                       ///< deg; camera pitch away from nadir
  int leaves_min = 4, leaves_max = 6;             ///< true leaves per seedling (paper: 4-6)
  int weeds_min = 4, weeds_max = 12;              ///< weed plants per scene
  double grass_fraction = 0.3;                    ///< share of weeds that are upright grass-like tufts (taller)
  double exposure_min = 0.7, exposure_max = 1.5;  ///< gain range of normal frames
  double overexposed_fraction = 0.2;              ///< share of frames with gain 1.8-2.6 (clipped)
  double noise_sigma = 2.0;                       ///< grey levels of sensor noise
  int supersample = 2;                            ///< samples per pixel side (anti-aliasing)

  template <class V>
  void visit(V& v) {
    v("width", width, "px per eye (paper: 640)");
    v("height", height, "px per eye (paper: 480)");
    v("hfov_deg", hfov_deg, "deg; horizontal field of view (paper's lens: ~120 deg before rectification)");
    v("baseline", baseline, "m; stereo baseline (paper: 0.06)");
    v("distance_min", distance_min, "m; smallest working distance (paper: 0.5)");
    v("distance_max", distance_max, "m; largest working distance (paper: 2.0 overall; 0.8 typical for seedlings)");
    v("tilt_max_deg", tilt_max_deg, "deg; largest camera tilt from nadir");
    v("leaves_min", leaves_min, "fewest true leaves (paper: 4)");
    v("leaves_max", leaves_max, "most true leaves (paper: 6)");
    v("weeds_min", weeds_min, "fewest weed plants per scene");
    v("weeds_max", weeds_max, "most weed plants per scene");
    v("grass_fraction", grass_fraction, "share of grass-like (taller) weeds");
    v("exposure_min", exposure_min, "smallest gain of normally exposed frames");
    v("exposure_max", exposure_max, "largest gain of normally exposed frames");
    v("overexposed_fraction", overexposed_fraction, "share of over-exposed frames (gain 1.8-2.6)");
    v("noise_sigma", noise_sigma, "grey levels of Gaussian sensor noise");
    v("supersample", supersample, "anti-aliasing samples per pixel side");
  }
  StereoRigModel rig() const;
};

struct SeedlingPair {
  ColorImage left, right;
  Image<float> disparity;         ///< px, left view; NaN where nothing was hit
  GrayImage mask;                 ///< 255 where the left view sees the seedling
  measure::EnvelopeBox envelope;  ///< of the seedling mesh (true physical extent)
  Eigen::Vector3d plane_normal;  ///< soil plane in the left camera frame: n . x + d = 0, n towards the camera side (up)
  double plane_d = 0;
  Eigen::Vector3d seedling_base;  ///< left camera frame, m
  double distance = 0, tilt_deg = 0, exposure = 1;
  int leaves = 0, weeds = 0;
};

/// Renders scene `index` of the data set `seed`. Throws Error("seedling simulator", ...) for an
/// invalid configuration.
SeedlingPair simulate_seedling_pair(const SeedlingSimConfig& cfg, std::uint64_t seed, int index);

/// A rendered checkerboard pair (grey, anti-aliased); board pose in the left camera frame.
struct CheckerboardPair {
  GrayImage left, right;
};
/// `cols` x `rows` inner corners, `square` m; board corner (0,0) at board-frame origin, board
/// z = 0 plane, mapped to the left camera by x = R_board x_b + t_board.
CheckerboardPair render_checkerboard_pair(const StereoRigModel& rig, int cols, int rows, double square,
                                          const Eigen::Matrix3d& R_board, const Eigen::Vector3d& t_board,
                                          int supersample = 4);
/// `n` random board poses fully visible in both views of `rig` (deterministic per seed).
std::vector<std::pair<Eigen::Matrix3d, Eigen::Vector3d>> random_board_poses(const StereoRigModel& rig, int cols,
                                                                            int rows, double square, int n,
                                                                            std::uint64_t seed);

/// Upper bounds of write_seedling_dataset()'s counts (a pair is ~1.5 MB on disk and ~0.1 s to
/// render; 10000 pairs is 15 GB already): a mistyped count must fail, not fill the disk.
inline constexpr int kMaxSeedlingPairs = 10000;
inline constexpr int kMaxCalibrationPairs = 1000;

/// Writes DIR/pair_NNN/{left,right,disparity,mask}.png + truth.json for `pairs` scenes and
/// DIR/calib/{left,right}_NNN.png for `calib_pairs` checkerboard pairs (9x6 inner corners,
/// 30 mm squares). disparity.png: 16-bit, value = disparity * 256, 0 = none. Files are written
/// atomically; `progress(done)` is called after each pair when given. Throws Error(dir, ...) for
/// pairs outside 0..kMaxSeedlingPairs or calib_pairs outside 0..kMaxCalibrationPairs. It writes
/// into `dir` directly: callers wanting all-or-nothing write into a temporary folder and rename it.
void write_seedling_dataset(const std::filesystem::path& dir, const SeedlingSimConfig& cfg, int pairs,
                            std::uint64_t seed, int calib_pairs, void (*progress)(int, void*) = nullptr,
                            void* progress_ctx = nullptr);

}  // namespace cropsight::sim
