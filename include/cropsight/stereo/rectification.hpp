#pragma once
// Bouguet rectification (cv::stereoRectify) of a calibrated pair and the rectified geometry the
// reconstruction needs: after remapping, both views share focal length f, principal point
// (cx, cy) and rows; a left pixel (u, v) with disparity d lies at Z = f * B / d, X = (u - cx) Z / f,
// Y = (v - cy) Z / f in the rectified left camera frame (x right, y down, z forward, metres).
#include <memory>
#include <string>
#include <utility>

#include "cropsight/core/image.hpp"
#include "cropsight/stereo/calibration.hpp"

namespace cropsight::stereo {

/// Pinhole geometry of a rectified pair.
struct RectifiedGeometry {
  int width = 0, height = 0;
  double f = 0;           ///< px
  double cx = 0, cy = 0;  ///< px, left view
  double cx_right = 0;    ///< px, right view principal point (== cx with zero-disparity rectification)
  double baseline = 0;    ///< m
};

class StereoRectifier {
 public:
  /// `alpha`: 0 keeps only valid pixels (zoomed in), 1 keeps all source pixels (black borders).
  explicit StereoRectifier(const StereoCalibration& calib, double alpha = 0.0);
  ~StereoRectifier();
  StereoRectifier(StereoRectifier&&) noexcept;
  StereoRectifier& operator=(StereoRectifier&&) noexcept;

  /// Remaps a raw pair. Throws Error(where, ...) when an image's size differs from the calibration.
  std::pair<ColorImage, ColorImage> rectify(const ColorImage& left, const ColorImage& right,
                                            const std::string& where = "stereo pair") const;
  const RectifiedGeometry& geometry() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// True when `calib` already describes a rectified pair (no distortion, R = I, T along x, equal
/// intrinsics): images need no remapping and rectified_geometry() reads f, cx, cy from K1.
bool is_rectified(const StereoCalibration& calib);
/// The rectified geometry of `calib`: read directly when is_rectified(), else Bouguet's.
RectifiedGeometry rectified_geometry(const StereoCalibration& calib);

/// A pair ready for matching: rectified images and their geometry.
struct RectifiedPair {
  ColorImage left, right;
  RectifiedGeometry geometry;
};

/// Rectifies a raw pair with `calib` (Bouguet), or passes it through when is_rectified(calib).
/// Throws Error(where, ...) when the left image's size differs from the calibration.
RectifiedPair rectify_pair(const StereoCalibration& calib, ColorImage left, ColorImage right,
                           const std::string& where = "stereo pair");

}  // namespace cropsight::stereo
