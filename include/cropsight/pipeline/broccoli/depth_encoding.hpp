#pragma once
// A depth frame as the 3-channel 8-bit image the broccoli head CNN reads
// (cnn.model of DetectorConfig; the training images of tools/broccoli_depth_coco).
// Channels, per pixel (no return: 0 / 128 / 0):
//   R: height above the soil, clamp((soil - z) / 0.5 m) · 255 (at least 1 where there is a return),
//      soil = the frame's 90th depth percentile (most of a nadir frame is soil or low canopy);
//   G: local relief, 128 + (mean z of the 15 x 15 window's returns - z) / 0.02 m · 127, in [1, 255]:
//      domes and florets above 128, hollows below;
//   B: depth gradient magnitude, clamp(|central difference of z| / 0.02 m per pixel) · 255 (depth
//      edges; a neighbour without a return counts as the pixel's own depth).
// Metric, so one network serves camera heights 1.1-1.5 m; the windows are in pixels.
#include <span>
#include <vector>

#include "cropsight/core/detection2d.hpp"
#include "cropsight/core/image.hpp"

namespace cropsight::pipeline::broccoli {

/// `depth` in sensor units, `depth_scale` metres per unit. Thread-safe (no shared state).
ColorImage encode_depth_for_cnn(const DepthImage& depth, double depth_scale);

/// One CNN instance on the frame: the pixel indices (ascending) inside `box` (image pixels, clipped
/// to the mask) where `mask` (the class mask, same size as the frame) is set and `z` (the organised
/// cloud's depths, width·height) is finite.
std::vector<int> mask_points_in_box(const Detection2D& box, const GrayImage& mask, std::span<const float> z);

}  // namespace cropsight::pipeline::broccoli
