#include "cropsight/pipeline/broccoli/depth_denoise.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "cropsight/core/error.hpp"

namespace cropsight::pipeline::broccoli {

float estimate_depth_noise(std::span<const std::uint16_t> depth, int width, int height, float scale, float min_depth,
                           float max_depth, std::vector<std::uint32_t>& histogram) {
  if (width <= 0 || height <= 0 || depth.size() != std::size_t(width) * std::size_t(height))
    throw Error("depth noise", "depth image size does not match width x height");
  if (!(scale > 0.0f)) throw Error("depth noise", "depth scale must be > 0");
  constexpr float kBin = 0.00025f;    // m
  constexpr std::size_t kBins = 400;  // up to 0.1 m; larger differences (edges) land in the last bin
  histogram.assign(kBins, 0);
  // The window in raw units, clamped to the 16-bit range before the conversion (a tiny scale or a
  // huge window would overflow it).
  auto raw = [](double units) { return std::uint32_t(std::clamp(units, 0.0, 65535.0)); };
  const std::uint32_t lo = raw(std::ceil(double(min_depth) / double(scale))),
                      hi = raw(std::floor(double(max_depth) / double(scale)));
  std::size_t count = 0;
  for (int v = 0; v < height; v += 4) {  // every 4th row: 27000 triples at 512x424, plenty for a median
    const std::uint16_t* row = depth.data() + std::size_t(v) * std::size_t(width);
    for (int u = 1; u + 1 < width; ++u) {
      const std::uint32_t a = row[u - 1], b = row[u], c = row[u + 1];
      if (a < lo || a > hi || b < lo || b > hi || c < lo || c > hi || a == 0 || b == 0 || c == 0) continue;
      const float d2 = float(std::abs(int(a) - 2 * int(b) + int(c))) * scale;
      ++histogram[std::min(kBins - 1, std::size_t(d2 / kBin))];
      ++count;
    }
  }
  if (count < 1000) return std::numeric_limits<float>::quiet_NaN();
  std::size_t seen = 0, half = count / 2;
  std::size_t bin = 0;
  for (; bin < kBins; ++bin) {
    seen += histogram[bin];
    if (seen > half) break;
  }
  const float median = (float(bin) + 0.5f) * kBin;
  return 1.4826f * median / std::sqrt(6.0f);
}

void bilateral_depth(std::span<const std::uint16_t> depth, int width, int height, float scale, float sigma_color,
                     int diameter, float sigma_space, std::vector<std::uint16_t>& out) {
  if (width <= 0 || height <= 0 || depth.size() != std::size_t(width) * std::size_t(height))
    throw Error("depth denoise", "depth image size does not match width x height");
  if (!(scale > 0.0f) || !(sigma_color > 0.0f) || !(sigma_space > 0.0f) || diameter < 1)
    throw Error("depth denoise", "scale, sigmas and diameter must be > 0");
  const cv::Mat raw(height, width, CV_16UC1, const_cast<std::uint16_t*>(depth.data()));
  cv::Mat metres, smooth;
  raw.convertTo(metres, CV_32F, double(scale));
  cv::bilateralFilter(metres, smooth, diameter, double(sigma_color), double(sigma_space), cv::BORDER_REPLICATE);
  out.resize(depth.size());
  const float inv = 1.0f / scale;
  for (int v = 0; v < height; ++v) {
    const float* s = smooth.ptr<float>(v);
    const std::uint16_t* r = depth.data() + std::size_t(v) * std::size_t(width);
    std::uint16_t* o = out.data() + std::size_t(v) * std::size_t(width);
    for (int u = 0; u < width; ++u)
      o[u] =
          r[u] == 0
              ? std::uint16_t(0)
              : std::uint16_t(std::clamp(std::lround(s[u] * inv), 1L, long(std::numeric_limits<std::uint16_t>::max())));
  }
}

}  // namespace cropsight::pipeline::broccoli
