#include "pipeline/broccoli/steps/deproject.hpp"

#include <limits>

#include "core/cpu_dispatch.hpp"

namespace cropsight::pipeline::broccoli::steps {

namespace {
// Branch-free with restrict pointers so that it vectorises (the AVX2 / AVX-512 clone picked at run
// time); -ffp-contract=off keeps the clones' values bit-identical to the scalar loop's.
CROPSIGHT_AVX2_CLONES void deproject_lanes(std::size_t n, const std::uint16_t* __restrict d, const float* __restrict rx,
                                           const float* __restrict ry, float scale, float lo, float hi,
                                           float* __restrict X, float* __restrict Y, float* __restrict Z) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (std::size_t i = 0; i < n; ++i) {
    const float zd = float(d[i]) * scale;
    const float z = (d[i] != 0) & (zd >= lo) & (zd <= hi) ? zd : nan;
    Z[i] = z;
    X[i] = rx[i] * z;
    Y[i] = ry[i] * z;
  }
}
}  // namespace

void ray_slopes(const CameraIntrinsics& camera, std::vector<float>& rx, std::vector<float>& ry) {
  const int w = camera.width, h = camera.height;
  rx.resize(std::size_t(w) * std::size_t(h));
  ry.resize(rx.size());
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      rx[std::size_t(v) * w + u] = float((u - camera.cx) / camera.fx);
      ry[std::size_t(v) * w + u] = float((v - camera.cy) / camera.fy);
    }
}

void deproject_depth(std::size_t n, const std::uint16_t* d, const float* rx, const float* ry, float scale, float lo,
                     float hi, float* X, float* Y, float* Z) {
  deproject_lanes(n, d, rx, ry, scale, lo, hi, X, Y, Z);
}

}  // namespace cropsight::pipeline::broccoli::steps
