#include "cropsight/pipeline/broccoli/depth_encoding.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace cropsight::pipeline::broccoli {

ColorImage encode_depth_for_cnn(const DepthImage& depth, double depth_scale) {
  const int w = depth.width, h = depth.height;
  const float scale = float(depth_scale);
  ColorImage out(w, h, Rgb8{0, 128, 0});
  cv::Mat z(h, w, CV_32F), valid(h, w, CV_32F);
  std::vector<float> values;
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const std::uint16_t d = depth.at(u, v);
      z.at<float>(v, u) = d ? float(d) * scale : 0.0f;
      valid.at<float>(v, u) = d ? 1.0f : 0.0f;
      if (d) values.push_back(float(d) * scale);
    }
  if (values.empty()) return out;
  const std::size_t k = std::size_t(double(values.size()) * 0.9);
  std::nth_element(values.begin(), values.begin() + long(k), values.end());
  const float soil = values[k];
  // Window sums of depth and of returns (OpenCV's default border, reflect 101, as in training).
  cv::Mat sum_z, sum_valid;
  cv::boxFilter(z, sum_z, CV_32F, cv::Size(15, 15), cv::Point(-1, -1), false);
  cv::boxFilter(valid, sum_valid, CV_32F, cv::Size(15, 15), cv::Point(-1, -1), false);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const float zz = z.at<float>(v, u);
      if (zz <= 0.0f) continue;
      const float height = std::clamp((soil - zz) / 0.5f, 0.0f, 1.0f);
      const float n = sum_valid.at<float>(v, u);
      const float mean = n > 0.0f ? sum_z.at<float>(v, u) / n : zz;
      const float relief = std::clamp(128.0f + (mean - zz) / 0.02f * 127.0f, 1.0f, 255.0f);
      auto at = [&](int uu, int vv) {
        uu = std::clamp(uu, 0, w - 1), vv = std::clamp(vv, 0, h - 1);
        const float q = z.at<float>(vv, uu);
        return q > 0.0f ? q : zz;
      };
      const float gx = 0.5f * (at(u + 1, v) - at(u - 1, v)), gy = 0.5f * (at(u, v + 1) - at(u, v - 1));
      const float grad = std::clamp(std::sqrt(gx * gx + gy * gy) / 0.02f, 0.0f, 1.0f);
      out.at(u, v) =
          Rgb8{std::uint8_t(std::max(1.0f, height * 255.0f)), std::uint8_t(relief), std::uint8_t(grad * 255.0f)};
    }
  return out;
}

std::vector<int> mask_points_in_box(const Detection2D& box, const GrayImage& mask, std::span<const float> z) {
  const int w = mask.width;
  const int u0 = std::max(0, int(std::floor(box.x1))), u1 = std::min(w, int(std::ceil(box.x2)));
  const int v0 = std::max(0, int(std::floor(box.y1))), v1 = std::min(mask.height, int(std::ceil(box.y2)));
  std::vector<int> pixels;  // row-major scan: ascending
  for (int v = v0; v < v1; ++v)
    for (int u = u0; u < u1; ++u) {
      const std::size_t i = std::size_t(v) * std::size_t(w) + std::size_t(u);
      if (mask.data[i] && std::isfinite(z[i])) pixels.push_back(int(i));
    }
  return pixels;
}

}  // namespace cropsight::pipeline::broccoli
