#include "cropsight/core/organized_cloud.hpp"

#include <limits>

#include "cropsight/core/error.hpp"
#include "cropsight/core/rgbd_frame.hpp"

namespace cropsight {

namespace {
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
}

OrganizedCloud::OrganizedCloud(int w, int h)
    : width(w), height(h), x(std::size_t(w) * h, kNaN), y(std::size_t(w) * h, kNaN), z(std::size_t(w) * h, kNaN) {}

std::size_t OrganizedCloud::count_valid() const {
  std::size_t n = 0;
  for (float v : z) n += std::isfinite(v) ? 1 : 0;
  return n;
}

void OrganizedCloud::allocate_normals() {
  nx.assign(size(), kNaN);
  ny.assign(size(), kNaN);
  nz.assign(size(), kNaN);
  curvature.assign(size(), kNaN);
}

OrganizedCloud to_organized_cloud(const RgbdFrame& frame, float min_depth, float max_depth) {
  const auto& cam = frame.camera;
  const auto& depth = frame.depth;
  if (depth.width != cam.width || depth.height != cam.height)
    throw Error("frame " + std::to_string(frame.index), "depth image size differs from camera size");
  OrganizedCloud cloud(depth.width, depth.height);
  const float scale = float(cam.depth_scale);
  // Precompute per-column and per-row rays: x = (u - cx)/fx * z, y = (v - cy)/fy * z.
  std::vector<float> ray_x(depth.width), ray_y(depth.height);
  for (int u = 0; u < depth.width; ++u) ray_x[u] = float((u - cam.cx) / cam.fx);
  for (int v = 0; v < depth.height; ++v) ray_y[v] = float((v - cam.cy) / cam.fy);
  for (int v = 0; v < depth.height; ++v) {
    const std::uint16_t* row = depth.row(v);
    for (int u = 0; u < depth.width; ++u) {
      const std::uint16_t d = row[u];
      if (d == 0) continue;
      const float z = float(d) * scale;
      if (z < min_depth || z > max_depth) continue;
      const std::size_t i = std::size_t(v) * depth.width + u;
      cloud.x[i] = ray_x[u] * z;
      cloud.y[i] = ray_y[v] * z;
      cloud.z[i] = z;
    }
  }
  if (!frame.color.empty()) cloud.color = frame.color.data;
  if (!frame.labels.empty()) cloud.labels = frame.labels.data;
  return cloud;
}

}  // namespace cropsight
