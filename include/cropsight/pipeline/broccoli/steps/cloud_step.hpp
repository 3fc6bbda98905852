#pragma once
// Depth image → organised cloud, the broccoli detector's first step (StageTimer "cloud", with
// "denoise" inside it):
//
//   [range.soil_relative or range.reference_range > 0: the soil's depth, a percentile of the
//    frame's depths → the window's far end and the frame's OES thresholds]
//   [denoise.above > 0: the depth noise estimate; a noisier frame is bilateral-filtered]
//   deprojection and depth window in one pass: z = raw · depth_scale (m), NaN when the raw depth
//   is 0 or z lies outside [depth.min_depth, far end]; x = z (u - cx) / fx, y = z (v - cy) / fy
//
// The cloud is in metres in the camera frame (x right, y down, z forward), one point per pixel.
// Its buffers, the per-pixel ray slopes (recomputed only when the camera changes), the
// histograms and the filtered depth are reused from frame to frame.
#include <cstdint>
#include <vector>

#include "cropsight/core/organized_cloud.hpp"
#include "cropsight/core/rgbd_frame.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/geometry/depth_filter.hpp"
#include "cropsight/pipeline/broccoli/depth_denoise.hpp"
#include "cropsight/pipeline/broccoli/detector_config.hpp"
#include "cropsight/pipeline/broccoli/steps/frame_state.hpp"

namespace cropsight::pipeline::broccoli::steps {

class CloudStep {
 public:
  /// `oes` is scaled per frame with range.reference_range (FrameConditions::oes).
  CloudStep(geometry::DepthRangeConfig depth, DepthDenoiseConfig denoise, RangeConfig range,
            segmentation::OesConfig oes);

  /// Fills `cloud` (x, y, z; labels copied from the frame's, or cleared) and returns what it
  /// learnt of the frame. Throws Error when the depth or label image's size differs from the
  /// camera's, or depth.min_depth > depth.max_depth.
  FrameConditions run(const RgbdFrame& frame, OrganizedCloud& cloud, StageTimer& timer);

 private:
  // The window's far end (m) and the soil depth and OES thresholds of `c` for this frame.
  float apply_range(const RgbdFrame& frame, FrameConditions& c);
  // The depth to deproject: the frame's, or its filtered copy when it is noisy.
  const std::uint16_t* denoise(const RgbdFrame& frame, float max_depth, FrameConditions& c, StageTimer& timer);

  geometry::DepthRangeConfig depth_;
  DepthDenoiseConfig denoise_;
  RangeConfig range_;
  segmentation::OesConfig oes_;
  // Per pixel (u - cx) / fx and (v - cy) / fy of `ray_camera_`: deprojection is two multiplies.
  std::vector<float> ray_x_, ray_y_;
  CameraIntrinsics ray_camera_;
  std::vector<std::uint32_t> depth_histogram_, noise_bins_;
  std::vector<std::uint16_t> denoised_;
};

}  // namespace cropsight::pipeline::broccoli::steps
