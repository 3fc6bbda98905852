#include "cropsight/geometry/concave_creases.hpp"

#include <cmath>
#include <numbers>

#include "cropsight/core/error.hpp"

namespace cropsight::geometry {

void mark_concave_creases(const OrganizedCloud& cloud, std::span<const int> pixels, const ConcaveCreaseOptions& options,
                          std::span<std::uint8_t> marks) {
  if (!(options.angle_deg > 0.0f && options.angle_deg < 180.0f))
    throw Error("concave creases", "angle_deg must lie in (0, 180)");
  if (options.step < 1) throw Error("concave creases", "step must be >= 1");
  if (cloud.nx.size() != cloud.size()) throw Error("concave creases", "the cloud has no normals");
  if (marks.size() != cloud.size()) throw Error("concave creases", "marks must hold one entry per pixel");
  const int w = cloud.width, h = cloud.height, step = options.step;
  const float cos_max = std::cos(options.angle_deg * std::numbers::pi_v<float> / 180.0f);
  const float *X = cloud.x.data(), *Y = cloud.y.data(), *Z = cloud.z.data();
  const float *NX = cloud.nx.data(), *NY = cloud.ny.data(), *NZ = cloud.nz.data();
  auto test = [&](int a, int b) {
    const float dot = NX[a] * NX[b] + NY[a] * NY[b] + NZ[a] * NZ[b];
    if (!(dot < cos_max)) return;  // NaN (no normal) compares false: not a crease
    const float convexity =
        (NX[a] - NX[b]) * (X[a] - X[b]) + (NY[a] - NY[b]) * (Y[a] - Y[b]) + (NZ[a] - NZ[b]) * (Z[a] - Z[b]);
    if (convexity < 0.0f) marks[std::size_t(a)] = marks[std::size_t(b)] = 1;
  };
  // Ascending indices (the usual case) walk the rows without a division per pixel.
  int v = 0, row_start = 0;
  for (int p : pixels) {
    if (p < 0 || std::size_t(p) >= cloud.size()) throw Error("concave creases", "pixel index outside the cloud");
    if (p < row_start || p >= row_start + w) {
      v = p / w;
      row_start = v * w;
    }
    const int u = p - row_start;
    if (u + step < w) test(p, p + step);
    if (v + step < h) test(p, p + step * w);
  }
}

}  // namespace cropsight::geometry
