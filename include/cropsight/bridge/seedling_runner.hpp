#pragma once
// The seedling pipeline (pipeline::seedling::Pipeline, SGM + GMM on a rectified stereo pair)
// behind a C++17 header, for the ROS node. process() keeps no state between pairs; one runner
// per thread. Errors: cropsight::Error naming the file or input.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "cropsight/pipeline/seedling/frame_result.hpp"

namespace cropsight::bridge {

struct RgbImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  ///< width*height*3, R G B, row-major
};

/// Rectified geometry of a pair (stereo::RectifiedGeometry): what a ROS stereo pair's two
/// camera_info P matrices give (f = P[0], cx = P[2], cy = P[6], baseline = -P_right[3] / P_right[0]).
struct StereoGeometry {
  int width = 0, height = 0;
  double f = 0;           ///< px
  double cx = 0, cy = 0;  ///< px, left view
  double cx_right = 0;    ///< px, right view
  double baseline = 0;    ///< m
};

class SeedlingRunner {
 public:
  /// preset: a name under configs/ (default "seedling") or a YAML path; sets: "key=value".
  SeedlingRunner(const std::string& preset, const std::vector<std::string>& sets);
  ~SeedlingRunner();
  SeedlingRunner(const SeedlingRunner&) = delete;
  SeedlingRunner& operator=(const SeedlingRunner&) = delete;
  /// Throws Error(where, ...) when a size differs from the geometry.
  pipeline::seedling::FrameResult process(const RgbImage& left, const RgbImage& right, const StereoGeometry& g,
                                          const std::string& where = "stereo pair") const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// A raw pair read from PNG files and rectified with a calibration YAML (stereo::rectify_pair),
/// as `detect seedling` does: for tools and tests that feed the node what the CLI sees.
struct RectifiedPairBuffers {
  RgbImage left, right;
  StereoGeometry geometry;
};
RectifiedPairBuffers read_rectified_pair(const std::string& calib_yaml, const std::string& left_png,
                                         const std::string& right_png);

}  // namespace cropsight::bridge
