#include "cropsight/report/render.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "cropsight/core/error.hpp"

namespace cropsight::report {

DepthRange robust_depth_range(const DepthImage& depth, double depth_scale) {
  std::vector<std::uint16_t> valid;
  valid.reserve(depth.size());
  for (std::uint16_t d : depth.data)
    if (d != 0) valid.push_back(d);
  if (valid.empty()) return {};
  auto at = [&](double q) {
    const std::size_t k = std::min(valid.size() - 1, std::size_t(q * double(valid.size() - 1) + 0.5));
    std::nth_element(valid.begin(), valid.begin() + std::ptrdiff_t(k), valid.end());
    return double(valid[k]) * depth_scale;
  };
  DepthRange r{at(0.02), at(0.98)};
  if (r.far_m - r.near_m < 0.01) {
    const double mid = 0.5 * (r.near_m + r.far_m);
    r = {mid - 0.005, mid + 0.005};
  }
  return r;
}

namespace {
// Raw values -> turbo colours: `index(value)` in [0, 255] (255 = the red end); value 0 = black.
template <class Index>
ColorImage turbo_image(const DepthImage& raw, Index index_of) {
  cv::Mat index(raw.height, raw.width, CV_8UC1);
  for (int v = 0; v < raw.height; ++v) {
    const std::uint16_t* in = raw.row(v);
    auto* out = index.ptr<std::uint8_t>(v);
    for (int u = 0; u < raw.width; ++u)
      out[u] = std::uint8_t(std::lround(255.0 * std::clamp(index_of(in[u]), 0.0, 1.0)));
  }
  cv::Mat bgr;
  cv::applyColorMap(index, bgr, cv::COLORMAP_TURBO);
  ColorImage img(raw.width, raw.height);
  for (int v = 0; v < raw.height; ++v) {
    const auto* p = bgr.ptr<cv::Vec3b>(v);
    const std::uint16_t* in = raw.row(v);
    Rgb8* out = img.row(v);
    for (int u = 0; u < raw.width; ++u) out[u] = in[u] == 0 ? Rgb8{0, 0, 0} : Rgb8{p[u][2], p[u][1], p[u][0]};
  }
  return img;
}
}  // namespace

ColorImage depth_colormap(const DepthImage& depth, double depth_scale, const DepthRange& range) {
  // Near = the red end of turbo.
  const double span = std::max(1e-9, range.far_m - range.near_m);
  return turbo_image(depth, [&](std::uint16_t d) { return 1.0 - (double(d) * depth_scale - range.near_m) / span; });
}

ColorImage disparity_colormap(const DepthImage& disparity_x256) {
  // The robust range of the raw values (scale 1), large disparity = near = red.
  const DepthRange r = robust_depth_range(disparity_x256, 1.0);
  const double span = std::max(1e-9, r.far_m - r.near_m);
  return turbo_image(disparity_x256, [&](std::uint16_t d) { return (double(d) - r.near_m) / span; });
}

ColorImage side_by_side(const std::vector<ColorImage>& images, int gap, Rgb8 fill) {
  int width = 0, height = 0;
  for (const ColorImage& im : images) {
    width += im.width + (width > 0 ? gap : 0);
    height = std::max(height, im.height);
  }
  ColorImage out(width, height, fill);
  int offset = 0;
  for (const ColorImage& im : images) {
    for (int v = 0; v < im.height; ++v) std::copy(im.row(v), im.row(v) + im.width, out.row(v) + offset);
    offset += im.width + gap;
  }
  return out;
}

ColorImage depth_colormap(const DepthImage& depth, double depth_scale) {
  return depth_colormap(depth, depth_scale, robust_depth_range(depth, depth_scale));
}

Rgb8 label_color(std::uint32_t id) {
  if (id == 0) return {40, 40, 40};
  // HSV with hue stepped by the golden ratio: neighbouring ids get far-apart hues.
  const double h = std::fmod(double(id) * 0.6180339887498949, 1.0) * 6.0;
  const double s = 0.7, val = 0.95;
  const int i = int(h);
  const double f = h - i, p = val * (1 - s), q = val * (1 - s * f), t = val * (1 - s * (1 - f));
  double r = 0, g = 0, b = 0;
  switch (i % 6) {
    case 0:
      r = val, g = t, b = p;
      break;
    case 1:
      r = q, g = val, b = p;
      break;
    case 2:
      r = p, g = val, b = t;
      break;
    case 3:
      r = p, g = q, b = val;
      break;
    case 4:
      r = t, g = p, b = val;
      break;
    default:
      r = val, g = p, b = q;
      break;
  }
  auto c = [](double x) { return std::uint8_t(std::lround(255.0 * x)); };
  return {c(r), c(g), c(b)};
}

ColorImage label_colormap(const LabelImage& labels) {
  ColorImage img(labels.width, labels.height);
  for (std::size_t i = 0; i < labels.size(); ++i) img.data[i] = label_color(labels.data[i]);
  return img;
}

void draw_label_outlines(ColorImage& image, const LabelImage& labels, Rgb8 color) {
  if (image.width != labels.width || image.height != labels.height)
    throw Error("outline", "image is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                               " but labels are " + std::to_string(labels.width) + "x" + std::to_string(labels.height));
  const int w = labels.width, h = labels.height;
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      const std::uint16_t id = labels.at(u, v);
      if (id == 0) continue;
      const bool edge = (u > 0 && labels.at(u - 1, v) != id) || (u + 1 < w && labels.at(u + 1, v) != id) ||
                        (v > 0 && labels.at(u, v - 1) != id) || (v + 1 < h && labels.at(u, v + 1) != id);
      if (edge) image.at(u, v) = color;
    }
  }
}

ColorImage upscale(const ColorImage& image, int factor) {
  if (factor <= 1) return image;
  ColorImage out(image.width * factor, image.height * factor);
  for (int v = 0; v < out.height; ++v)
    for (int u = 0; u < out.width; ++u) out.at(u, v) = image.at(u / factor, v / factor);
  return out;
}

}  // namespace cropsight::report
