// measure/orientation: the long axis of a mask, by PCA of its pixel centres or by an ellipse fit
// of its largest outer contour; both turned into the trigonometric angle in [0, π).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "cropsight/geometry/pca.hpp"
#include "cropsight/measure/orientation.hpp"
#include "stereo/cv_convert.hpp"

namespace cropsight::measure {

namespace {

// Image direction (dx, dy) with y down → trigonometric angle (y up) in [0, π).
double trig_angle(double dx, double dy) {
  double a = std::atan2(-dy, dx);
  if (a < 0) a += std::numbers::pi;
  if (a >= std::numbers::pi) a -= std::numbers::pi;
  return a;
}

AxisEstimate pca_axis(const GrayImage& mask, int min_pixels) {
  std::vector<Eigen::Vector2d> pts;
  pts.reserve(mask.size() / 2);
  for (int v = 0; v < mask.height; ++v) {
    const std::uint8_t* row = mask.row(v);
    for (int u = 0; u < mask.width; ++u)
      if (row[u]) pts.emplace_back(u + 0.5, v + 0.5);
  }
  AxisEstimate e;
  e.pixels = pts.size();
  if (pts.size() < std::size_t(std::max(min_pixels, 2))) return e;
  const auto p = geometry::pca(pts, geometry::EigenMethod::closed_form);
  // For a filled ellipse with semi-axes a, b the variances along its axes are a²/4 and b²/4.
  e.major_px = 4.0 * std::sqrt(std::max(0.0, p.eigenvalues(1)));
  e.minor_px = 4.0 * std::sqrt(std::max(0.0, p.eigenvalues(0)));
  e.angle_rad = trig_angle(p.major().x(), p.major().y());
  e.ok = true;
  return e;
}

AxisEstimate ellipse_axis(const GrayImage& mask, int min_pixels) {
  AxisEstimate e;
  for (auto px : mask.data) e.pixels += px != 0;
  if (e.pixels < std::size_t(min_pixels)) return e;
  cv::Mat m = stereo::detail::view(mask).clone();  // findContours wants a binary copy it may keep
  cv::threshold(m, m, 0, 255, cv::THRESH_BINARY);
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(m, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  const std::vector<cv::Point>* best = nullptr;
  double best_area = -1;
  for (const auto& c : contours)
    if (const double a = cv::contourArea(c); a > best_area) best_area = a, best = &c;
  if (!best || best->size() < 5) return e;
  const cv::RotatedRect r = cv::fitEllipse(*best);
  // RotatedRect: `width` lies along `angle` degrees, measured from x towards y (clockwise as the
  // image is viewed, since y points down); `height` is perpendicular.
  const double t = r.angle * std::numbers::pi / 180.0;
  const bool width_major = r.size.width >= r.size.height;
  const double dx = width_major ? std::cos(t) : -std::sin(t), dy = width_major ? std::sin(t) : std::cos(t);
  e.major_px = std::max(r.size.width, r.size.height);
  e.minor_px = std::min(r.size.width, r.size.height);
  e.angle_rad = trig_angle(dx, dy);
  e.ok = true;
  return e;
}

}  // namespace

AxisEstimate mask_axis(const GrayImage& mask, OrientationAxis axis, int min_pixels) {
  AxisEstimate e = axis == OrientationAxis::pca ? pca_axis(mask, min_pixels) : ellipse_axis(mask, min_pixels);
  if (e.ok && e.major_px > 0)
    e.confidence = std::clamp(1.0 - (e.minor_px * e.minor_px) / (e.major_px * e.major_px), 0.0, 1.0);
  return e;
}

}  // namespace cropsight::measure
