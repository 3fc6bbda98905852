#pragma once
// Images people look at: depth colour maps, label colour maps and instance outlines drawn over
// any image. Pure functions on cropsight images (no OpenCV in this header); the report page,
// `cropsight render` and detection overlays all use them.
#include <cstdint>

#include "cropsight/core/image.hpp"

namespace cropsight::report {

/// Depth range shown by a colour map, metres.
struct DepthRange {
  double near_m = 0.0;
  double far_m = 1.0;
};

/// The 2nd..98th percentile of the valid depths (metres = raw * depth_scale), so a few flying
/// pixels do not wash out the map; [0, 1] m when there is no valid depth. Widened to at least
/// 1 cm so that a flat scene still maps to distinct colours.
DepthRange robust_depth_range(const DepthImage& depth, double depth_scale);

/// Turbo colour map (OpenCV COLORMAP_TURBO): near = red, far = blue; no return (0) = black.
ColorImage depth_colormap(const DepthImage& depth, double depth_scale, const DepthRange& range);
/// Same, with robust_depth_range().
ColorImage depth_colormap(const DepthImage& depth, double depth_scale);

/// A stable, distinct colour per instance id (golden-ratio hue steps); id 0 = dark grey.
Rgb8 label_color(std::uint32_t id);
/// Every pixel coloured by label_color() of its id.
ColorImage label_colormap(const LabelImage& labels);

/// Paints, in `image`, every labelled pixel (id != 0) that has a 4-neighbour with a different id,
/// i.e. the inner boundary of each instance. `image` and `labels` must have the same size.
/// Throws Error("outline", ...) otherwise.
void draw_label_outlines(ColorImage& image, const LabelImage& labels, Rgb8 color = {255, 255, 255});

/// Nearest-neighbour upscale by an integer factor (small frames are unreadable at 1:1 in a page).
ColorImage upscale(const ColorImage& image, int factor);

}  // namespace cropsight::report
