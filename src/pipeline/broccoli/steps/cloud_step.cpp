#include "cropsight/pipeline/broccoli/steps/cloud_step.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "cropsight/core/error.hpp"
#include "pipeline/broccoli/steps/deproject.hpp"
#include "pipeline/broccoli/steps/soil_range.hpp"

namespace cropsight::pipeline::broccoli::steps {

namespace {
bool same_ray_camera(const CameraIntrinsics& a, const CameraIntrinsics& b) {
  return a.width == b.width && a.height == b.height && a.fx == b.fx && a.fy == b.fy && a.cx == b.cx && a.cy == b.cy;
}
}  // namespace

CloudStep::CloudStep(geometry::DepthRangeConfig depth, DepthDenoiseConfig denoise, RangeConfig range,
                     segmentation::OesConfig oes)
    : depth_(depth), denoise_(denoise), range_(range), oes_(oes) {}

FrameConditions CloudStep::run(const RgbdFrame& frame, OrganizedCloud& cloud, StageTimer& timer) {
  auto t = timer.scope("cloud");
  const int w = frame.depth.width, h = frame.depth.height;
  if (w != frame.camera.width || h != frame.camera.height)
    throw Error("frame " + std::to_string(frame.index), "depth image size differs from the camera's");
  const std::size_t n = std::size_t(w) * std::size_t(h);
  if (!same_ray_camera(ray_camera_, frame.camera) || ray_x_.size() != n) {
    ray_slopes(frame.camera, ray_x_, ray_y_);
    ray_camera_ = frame.camera;
  }
  cloud.width = w;
  cloud.height = h;
  cloud.x.resize(n);
  cloud.y.resize(n);
  cloud.z.resize(n);
  if (!(depth_.min_depth <= depth_.max_depth)) throw Error("depth range", "min_depth must not exceed max_depth");
  FrameConditions c;
  const float max_depth = apply_range(frame, c);
  const std::uint16_t* depth = denoise(frame, max_depth, c, timer);
  deproject_depth(n, depth, ray_x_.data(), ray_y_.data(), float(frame.camera.depth_scale), depth_.min_depth, max_depth,
                  cloud.x.data(), cloud.y.data(), cloud.z.data());
  if (!frame.labels.empty()) {
    if (frame.labels.width != w || frame.labels.height != h)
      throw Error("frame " + std::to_string(frame.index), "label image size differs from the depth image");
    cloud.labels.assign(frame.labels.data.begin(), frame.labels.data.end());
  } else {
    cloud.labels.clear();
  }
  return c;
}

// Range-aware options: the window's far end and the OES thresholds follow the soil's depth.
float CloudStep::apply_range(const RgbdFrame& frame, FrameConditions& c) {
  c.oes = oes_;
  if (!(range_.soil_relative || range_.reference_range > 0.0f)) return depth_.max_depth;
  c.soil_depth = depth_percentile(frame.depth.data, frame.depth.width, frame.depth.height,
                                  float(frame.camera.depth_scale), range_.soil_percentile, depth_histogram_);
  if (!std::isfinite(c.soil_depth)) return depth_.max_depth;
  float max_depth = depth_.max_depth;
  if (range_.soil_relative) {
    const float floor = range_.extend_only ? depth_.max_depth : depth_.min_depth;
    max_depth = std::max(floor, c.soil_depth - range_.min_height_above_soil);
  }
  if (range_.reference_range > 0.0f) {
    // The heads' range: their typical height above the soil, never nearer than the window allows.
    const float r = std::max(depth_.min_depth + 0.1f, c.soil_depth - range_.head_height);
    c.oes = oes_at_range(oes_, r / range_.reference_range);
  }
  return max_depth;
}

// Noise-adaptive denoising (denoise.above > 0): only a frame noisier than the threshold is filtered.
const std::uint16_t* CloudStep::denoise(const RgbdFrame& frame, float max_depth, FrameConditions& c,
                                        StageTimer& timer) {
  if (!(denoise_.above > 0.0f)) return frame.depth.data.data();
  auto t = timer.scope("denoise");
  const int w = frame.depth.width, h = frame.depth.height;
  const float scale = float(frame.camera.depth_scale);
  c.noise_sigma = estimate_depth_noise(frame.depth.data, w, h, scale, depth_.min_depth, max_depth, noise_bins_);
  if (!(c.noise_sigma > denoise_.above)) return frame.depth.data.data();
  bilateral_depth(frame.depth.data, w, h, scale, denoise_.sigma_factor * c.noise_sigma, denoise_.diameter,
                  denoise_.sigma_space, denoised_);
  c.denoised = true;
  return denoised_.data();
}

}  // namespace cropsight::pipeline::broccoli::steps
