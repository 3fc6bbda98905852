// Jet colour map, inverted so that near is red as in the paper's images (see depth_colormap.hpp).
#include "cropsight/io/depth_colormap.hpp"

#include <algorithm>

namespace cropsight::io {

Rgb8 depth_color(float z, float near_m, float far_m) {
  if (!(z > 0)) return {0, 0, 0};
  const float span = far_m > near_m ? far_m - near_m : 1.f;
  // t = 0 far (blue) .. 1 near (red): the classic jet ramp on t.
  const float t = 1.f - std::clamp((z - near_m) / span, 0.f, 1.f);
  auto ramp = [](float x) { return std::clamp(1.5f - std::abs(4.f * x), 0.f, 1.f); };
  const float r = ramp(t - 0.75f), g = ramp(t - 0.5f), b = ramp(t - 0.25f);
  auto byte = [](float c) { return std::uint8_t(c * 255.f + 0.5f); };
  return {byte(r), byte(g), byte(b)};
}

ColorImage colorize_depth(const Image<float>& depth_m, float near_m, float far_m) {
  ColorImage out(depth_m.width, depth_m.height);
  for (std::size_t i = 0; i < depth_m.data.size(); ++i) out.data[i] = depth_color(depth_m.data[i], near_m, far_m);
  return out;
}

}  // namespace cropsight::io
