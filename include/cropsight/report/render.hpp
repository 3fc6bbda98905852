#pragma once
// Images people look at: depth colour maps, label colour maps and instance outlines drawn over
// any image. Pure functions on cropsight images (no OpenCV in this header); the report page,
// `cropsight render` and detection overlays all use them.
#include <algorithm>
#include <cstdint>
#include <vector>

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

/// The part [x, x + width) x [y, y + height) of `image`, moved inside it where it sticks out (and
/// shrunk to the image when larger).
template <class T>
Image<T> crop(const Image<T>& image, int x, int y, int width, int height) {
  width = std::min(width, image.width), height = std::min(height, image.height);
  x = std::clamp(x, 0, image.width - width), y = std::clamp(y, 0, image.height - height);
  Image<T> out(width, height);
  for (int v = 0; v < height; ++v) std::copy(image.row(y + v) + x, image.row(y + v) + x + width, out.row(v));
  return out;
}

/// Turbo colour map of a stereo disparity image stored as value = disparity (px) x 256, 0 = none
/// (`stereo disparity`, the seedling simulator): large disparity (near) = red, small = blue, over
/// the 2nd..98th percentile of the valid values; no disparity = black.
ColorImage disparity_colormap(const DepthImage& disparity_x256);

/// The images next to each other, left to right, top-aligned, `gap` pixels of `fill` between
/// them; pixel (u, v) of image k lands at (u + offset_k, v), offset_k = sum of the earlier
/// widths and gaps.
ColorImage side_by_side(const std::vector<ColorImage>& images, int gap = 8, Rgb8 fill = {255, 255, 255});

}  // namespace cropsight::report
