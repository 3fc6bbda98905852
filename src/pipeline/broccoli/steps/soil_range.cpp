#include "pipeline/broccoli/steps/soil_range.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cropsight::pipeline::broccoli::steps {

// Every 4th row: a quarter of the cost (the cloud stage on uk-2001 took 0.41-0.45 ms with every
// row, 0.26-0.28 ms with every 4th).
float depth_percentile(const std::vector<std::uint16_t>& depth, int width, int height, float scale, float fraction,
                       std::vector<std::uint32_t>& hist) {
  constexpr float kBin = 0.005f;
  constexpr int kRowStep = 4;
  const float per_raw = scale / kBin;
  hist.assign(std::size_t(65535 * per_raw) + 2, 0);
  std::size_t valid = 0;
  for (int v = 0; v < height; v += kRowStep) {
    const std::uint16_t* row = depth.data() + std::size_t(v) * std::size_t(width);
    for (int u = 0; u < width; ++u)
      if (const std::uint16_t d = row[u]) ++hist[std::size_t(float(d) * per_raw)], ++valid;
  }
  if (valid * kRowStep < 1000) return std::numeric_limits<float>::quiet_NaN();
  const auto target = std::size_t(double(valid) * fraction);
  std::size_t seen = 0;
  for (std::size_t b = 0; b < hist.size(); ++b) {
    seen += hist[b];
    if (seen > target) return (float(b) + 0.5f) * kBin;
  }
  return (float(hist.size()) - 0.5f) * kBin;
}

// A surface's point count falls with the square of its range, its point spacing grows with it.
segmentation::OesConfig oes_at_range(const segmentation::OesConfig& oes, float s) {
  auto points = [&](int p) { return p > 0 ? std::max(1, int(std::lround(float(p) / (s * s)))) : p; };
  segmentation::OesConfig scaled = oes;
  scaled.min_size = points(oes.min_size);
  scaled.min_size_border = points(oes.min_size_border);
  scaled.max_size = std::max(scaled.min_size, points(oes.max_size));
  scaled.distance_tolerance = oes.distance_tolerance * s;
  return scaled;
}

}  // namespace cropsight::pipeline::broccoli::steps
