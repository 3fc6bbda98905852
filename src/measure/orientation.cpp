// measure/orientation: the widened box, the input checks, and the choice of segmentation.
#include "cropsight/measure/orientation.hpp"

#include <algorithm>
#include <cmath>

#include "measure/orientation_steps.hpp"
#include "stereo/cv_convert.hpp"

namespace cropsight::measure {

void validate(const OrientationConfig& cfg, const std::string& where) {
  check_config(cfg, where);
  if (cfg.canny_low > cfg.canny_high) throw Error(where, "'canny_low' must not exceed 'canny_high'");
}

GrayImage segment_potato(const ColorImage& roi, const OrientationConfig& cfg) {
  const cv::Mat rgb = stereo::detail::view(roi);
  cv::Mat mask;
  switch (cfg.segmentation) {
    case OrientationSegmentation::canny:
      mask = detail::segment_canny(rgb, cfg);
      break;
    case OrientationSegmentation::kmeans:
      mask = detail::segment_kmeans(rgb, cfg);
      break;
    case OrientationSegmentation::ours:
      mask = detail::segment_ours(rgb, cfg);
      break;
  }
  return stereo::detail::to_gray(mask);
}

namespace {

// A colourised depth map has no grey pixels but black ones (no depth): when most of the bright
// pixels of the region are grey, the caller passed an RGB or grey image as depth.
bool looks_grey(const ColorImage& im, int x0, int y0, int x1, int y1) {
  std::size_t bright = 0, grey = 0;
  for (int v = y0; v < y1; ++v)
    for (int u = x0; u < x1; ++u) {
      const Rgb8 p = im.at(u, v);
      const int hi = std::max({p.r, p.g, p.b}), lo = std::min({p.r, p.g, p.b});
      if (hi < 40) continue;
      ++bright;
      if (hi - lo <= 12) ++grey;
    }
  return bright > 0 && grey * 2 > bright;
}

}  // namespace

PixelRegion orientation_region(const Detection2D& box, const OrientationConfig& cfg, int width, int height,
                               int pad_px) {
  const double mx = cfg.box_margin * box.width() + pad_px, my = cfg.box_margin * box.height() + pad_px;
  // Pixels whose span [u, u + 1) meets the widened box, clipped to the image.
  return {std::max(0, int(std::floor(box.x1 - mx))), std::max(0, int(std::floor(box.y1 - my))),
          std::min(width, int(std::ceil(box.x2 + mx))), std::min(height, int(std::ceil(box.y2 + my)))};
}

OrientationResult estimate_orientation(const ColorImage& image, const Detection2D& box, const OrientationConfig& cfg,
                                       const std::string& where) {
  if (image.empty() || image.width <= 0 || image.height <= 0) throw Error(where, "empty image");
  if (!std::isfinite(box.x1) || !std::isfinite(box.y1) || !std::isfinite(box.x2) || !std::isfinite(box.y2) ||
      !(box.width() > 0) || !(box.height() > 0))
    throw Error(where, "empty or non-finite box");
  const auto [x0, y0, x1, y1] = orientation_region(box, cfg, image.width, image.height);
  if (x1 - x0 < 3 || y1 - y0 < 3) throw Error(where, "box outside the image (or under 3 px inside it)");
  if (cfg.input == OrientationInput::depth && looks_grey(image, x0, y0, x1, y1))
    throw Error(where, "input=depth expects a colourised depth image (near = red, far = blue), this one is grey");

  ColorImage roi(x1 - x0, y1 - y0);
  for (int v = y0; v < y1; ++v) std::copy(image.row(v) + x0, image.row(v) + x1, roi.row(v - y0));
  OrientationResult r;
  r.mask = segment_potato(roi, cfg);
  r.roi_x = x0;
  r.roi_y = y0;
  static_cast<AxisEstimate&>(r) = mask_axis(r.mask, cfg.axis, cfg.min_mask_pixels);
  return r;
}

}  // namespace cropsight::measure
