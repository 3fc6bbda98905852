#include "cropsight/report/cloud_view.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "cropsight/core/error.hpp"

namespace cropsight::report {

Eigen::Vector2f CloudView::pixel(const Eigen::Vector3f& p) const {
  return {(p.dot(right) - left) * px_per_unit, (top - p.dot(up)) * px_per_unit};
}

CloudView fit_cloud_view(const std::vector<Eigen::Vector3f>& points, const Eigen::Vector3f& right,
                         const Eigen::Vector3f& up, int width, float margin) {
  if (points.empty()) throw Error("cloud view", "no points to frame");
  if (width < 16) throw Error("cloud view", "width must be at least 16 px, got " + std::to_string(width));
  float x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (const auto& p : points) {
    x0 = std::min(x0, p.dot(right));
    x1 = std::max(x1, p.dot(right));
    y0 = std::min(y0, p.dot(up));
    y1 = std::max(y1, p.dot(up));
  }
  // A single point or a line still gets an area: the larger extent, or one unit.
  float extent = std::max(x1 - x0, y1 - y0);
  if (extent < 1e-6f) extent = 1.f;
  const auto widen = [&](float& lo, float& hi) {
    if (hi - lo < 1e-6f) {
      const float c = 0.5f * (lo + hi);
      lo = c - 0.5f * extent;
      hi = c + 0.5f * extent;
    }
    lo -= margin * extent;
    hi += margin * extent;
  };
  widen(x0, x1);
  widen(y0, y1);
  CloudView v;
  v.right = right;
  v.up = up;
  v.left = x0;
  v.top = y1;
  v.width = width;
  v.px_per_unit = float(width) / (x1 - x0);
  v.height = std::max(16, int(std::ceil((y1 - y0) * v.px_per_unit)));
  return v;
}

ColorImage render_cloud(const Cloud& cloud, const std::vector<Rgb8>& colors, const CloudView& view, int point_px,
                        Rgb8 background) {
  if (colors.size() != cloud.size())
    throw Error("cloud view",
                std::to_string(colors.size()) + " colours for " + std::to_string(cloud.size()) + " points");
  const Eigen::Vector3f toward = view.right.cross(view.up);
  std::vector<std::size_t> order(cloud.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  // Painter's order, stable so that equal depths keep the cloud's order (the same picture every run).
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return cloud.points[a].dot(toward) < cloud.points[b].dot(toward);
  });
  ColorImage img(view.width, view.height, background);
  const int half = point_px / 2;
  for (std::size_t k : order) {
    const Eigen::Vector2f q = view.pixel(cloud.points[k]);
    const int u0 = int(std::floor(q.x())) - half, v0 = int(std::floor(q.y())) - half;
    for (int v = std::max(0, v0); v < std::min(view.height, v0 + point_px); ++v)
      for (int u = std::max(0, u0); u < std::min(view.width, u0 + point_px); ++u) img.at(u, v) = colors[k];
  }
  return img;
}

}  // namespace cropsight::report
