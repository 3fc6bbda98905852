// Box completion over the depth surface (see depth_completion.hpp).
#include "depth_completion.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <utility>
#include <vector>

#include "cropsight/measure/depth_flood.hpp"

namespace cropsight::pipeline::potato::detail {

Detection2D complete_by_depth(const Detection2D& box, const cv::Mat& part, int roi_x, int roi_y,
                              const Image<float>& depth_m, const cv::Mat& labels, int own, const cv::Mat& opening,
                              const DepthCompletionRule& rule) {
  if (rule.grow <= 0 || depth_m.empty()) return box;
  // The blob's median depth.
  std::vector<float> values;
  for (int y = 0; y < part.rows; ++y) {
    const std::uint8_t* p = part.ptr<std::uint8_t>(y);
    const float* z = depth_m.row(roi_y + y) + roi_x;
    for (int x = 0; x < part.cols; ++x)
      if (p[x] && z[x] > 0) values.push_back(z[x]);
  }
  if (int(values.size()) < rule.min_depth_px) return box;
  auto mid = values.begin() + std::ptrdiff_t(values.size() / 2);
  std::nth_element(values.begin(), mid, values.end());
  const float lo = *mid - float(rule.band_m), hi = *mid + float(rule.band_m), step = float(rule.step_m);

  // The region it may grow into: the box widened by `grow` of its sides.
  const double gw = rule.grow * box.width(), gh = rule.grow * box.height();
  const cv::Rect region = cv::Rect(cv::Point(int(std::floor(box.x1 - gw)), int(std::floor(box.y1 - gh))),
                                   cv::Point(int(std::ceil(box.x2 + gw)), int(std::ceil(box.y2 + gh)))) &
                          cv::Rect(0, 0, depth_m.width, depth_m.height);
  cv::Mat grown = cv::Mat::zeros(region.size(), CV_8UC1);
  std::vector<std::pair<int, int>> stack;
  const auto fits = [&](int u, int v) {
    const float d = depth_m.at(u, v);
    const int l = labels.at<int>(v, u);
    return d >= lo && d <= hi && (l == 0 || l == own);
  };
  for (int y = 0; y < part.rows; ++y) {
    const std::uint8_t* p = part.ptr<std::uint8_t>(y);
    for (int x = 0; x < part.cols; ++x) {
      const int u = roi_x + x, v = roi_y + y;
      if (!p[x] || !region.contains(cv::Point(u, v))) continue;
      grown.at<std::uint8_t>(v - region.y, u - region.x) = 255;
      if (fits(u, v)) stack.emplace_back(u, v);
    }
  }
  measure::flood_depth(depth_m, region.x, region.y, region.br().x, region.br().y, step, stack, fits, [&](int u, int v) {
    std::uint8_t& g = grown.at<std::uint8_t>(v - region.y, u - region.x);
    if (g) return false;
    g = 255;
    return true;
  });
  // The opening scales with the potato: its diameter is `opening_fraction` x the grown region's
  // largest inscribed radius (half the potato's width), at least the detector's kernel. A root or
  // string at the potato's depth is far thinner than the potato, but near the camera it is wider
  // than the detector's fixed opening.
  cv::Mat distance;
  cv::distanceTransform(grown, distance, cv::DIST_L2, 3);
  double radius = 0;
  cv::minMaxLoc(distance, nullptr, &radius);
  const int k = std::max(opening.cols, int(std::lround(rule.opening_fraction * radius)));
  if (k >= 2) cv::morphologyEx(grown, grown, cv::MORPH_OPEN, cv::getStructuringElement(cv::MORPH_ELLIPSE, {k, k}));
  if (cv::countNonZero(grown) == 0) return box;
  const cv::Rect b = cv::boundingRect(grown) + region.tl();
  // A surface that runs on to the region's limit (not the image's edge) on two sides or more has
  // no rim: a backdrop or a wall at the potato's depth, not a potato. The colour box stays. (One
  // side is a root or a neighbour reaching in; the dev approaches need that side.)
  const int open_sides = int(b.x <= region.x && region.x > 0) + int(b.y <= region.y && region.y > 0) +
                         int(b.br().x >= region.br().x && region.br().x < depth_m.width) +
                         int(b.br().y >= region.br().y && region.br().y < depth_m.height);
  if (open_sides >= 2) return box;
  Detection2D out = box;
  out.x1 = std::min(box.x1, float(b.x));
  out.y1 = std::min(box.y1, float(b.y));
  out.x2 = std::max(box.x2, float(b.br().x));
  out.y2 = std::max(box.y2, float(b.br().y));
  return out;
}

}  // namespace cropsight::pipeline::potato::detail
