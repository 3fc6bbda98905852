// Concavity split of touching potatoes (see the header for the rule).
#include "concavity_split.hpp"

#include <algorithm>
#include <opencv2/imgproc.hpp>

namespace cropsight::pipeline::potato::detail {
namespace {

// The outline is simplified to within one pixel (its own quantisation) before the search, so the
// candidate cuts are the polygon's vertices (tens, not hundreds of contour pixels).
constexpr double kPolygonTolerancePx = 1.0;

double solidity(const std::vector<cv::Point>& poly) {
  if (poly.size() < 3) return 0;
  std::vector<cv::Point> hull;
  cv::convexHull(poly, hull);
  const double hull_area = cv::contourArea(hull);
  return hull_area > 0 ? cv::contourArea(poly) / hull_area : 0;
}

bool inside(const std::vector<cv::Point>& poly, cv::Point2f p) { return cv::pointPolygonTest(poly, p, false) >= 0; }

// The two polygons a cut between vertices a < b makes: a..b and b..end..a (both closed by the cut).
void halves(const std::vector<cv::Point>& poly, int a, int b, std::vector<cv::Point>& first,
            std::vector<cv::Point>& second) {
  first.assign(poly.begin() + a, poly.begin() + b + 1);
  second.assign(poly.begin() + b, poly.end());
  second.insert(second.end(), poly.begin(), poly.begin() + a + 1);
}

// Splits polygon `poly` into `out` (one or more polygons).
void split_polygon(const std::vector<cv::Point>& poly, const SplitRule& rule, double min_depth_px, int depth_left,
                   std::vector<std::vector<cv::Point>>& out) {
  const int n = int(poly.size());
  if (depth_left <= 0 || n < 8) return out.push_back(poly);
  std::vector<int> hull;
  cv::convexHull(poly, hull, false, false);
  std::vector<cv::Vec4i> defects;
  if (hull.size() >= 3) {
    try {
      cv::convexityDefects(poly, hull, defects);
    } catch (const cv::Exception&) {
      // A self-touching outline (non-monotonic hull indices): treat the blob as one potato.
      defects.clear();
    }
  }
  const double total = cv::contourArea(poly);
  double best = solidity(poly);  // a cut must make the parts more convex than the whole
  int cut_a = -1, cut_b = -1;
  std::vector<cv::Point> first, second;
  for (const cv::Vec4i& d : defects) {
    if (d[3] / 256.0 < min_depth_px) continue;  // depth is in 1/256 px
    const int i = d[2];
    for (int j = 0; j < n; ++j) {
      const int gap = std::min(std::abs(j - i), n - std::abs(j - i));
      if (gap < 3) continue;
      // The cut must run inside the blob: its quarter points and midpoint are inside.
      const cv::Point2f p(poly[i]), q(poly[j]);
      if (!inside(poly, 0.5f * (p + q)) || !inside(poly, 0.75f * p + 0.25f * q) || !inside(poly, 0.25f * p + 0.75f * q))
        continue;
      const int a = std::min(i, j), b = std::max(i, j);
      halves(poly, a, b, first, second);
      const double area1 = cv::contourArea(first), area2 = cv::contourArea(second);
      if (std::min(area1, area2) < rule.min_part_fraction * total) continue;
      // Both parts must look like potatoes (nearly convex): cutting a ragged blob (clutter, a
      // partly covered textured potato) makes it more convex too, but leaves ragged parts.
      const double s1 = solidity(first), s2 = solidity(second);
      if (std::min(s1, s2) < rule.min_part_solidity) continue;
      const double s = (area1 * s1 + area2 * s2) / (area1 + area2);
      if (s > best) best = s, cut_a = a, cut_b = b;
    }
  }
  if (cut_a < 0) return out.push_back(poly);
  halves(poly, cut_a, cut_b, first, second);
  split_polygon(first, rule, min_depth_px, depth_left - 1, out);
  split_polygon(second, rule, min_depth_px, depth_left - 1, out);
}

}  // namespace

int split_at_concavities(const cv::Mat& blob, const SplitRule& rule, std::vector<cv::Mat>& parts) {
  if (rule.depth_fraction <= 0 || rule.max_depth <= 0) return 1;
  cv::Mat padded, dist;
  cv::copyMakeBorder(blob, padded, 1, 1, 1, 1, cv::BORDER_CONSTANT, 0);
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(padded, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE, cv::Point(-1, -1));
  if (contours.empty()) return 1;
  const auto& outline = *std::max_element(contours.begin(), contours.end(),
                                          [](const auto& a, const auto& b) { return a.size() < b.size(); });
  std::vector<cv::Point> poly;
  cv::approxPolyDP(outline, poly, kPolygonTolerancePx, true);
  // Inscribed radius: the scale a notch's depth is compared with.
  cv::distanceTransform(padded, dist, cv::DIST_L2, cv::DIST_MASK_5);
  double radius = 0;
  cv::minMaxLoc(dist, nullptr, &radius);
  std::vector<std::vector<cv::Point>> polys;
  split_polygon(poly, rule, rule.depth_fraction * radius, rule.max_depth, polys);
  if (polys.size() < 2) return 1;
  for (const auto& p : polys) {
    cv::Mat part = cv::Mat::zeros(blob.size(), CV_8UC1);
    cv::fillPoly(part, std::vector<std::vector<cv::Point>>{p}, 255);
    parts.push_back(part & blob);
  }
  return int(polys.size());
}

}  // namespace cropsight::pipeline::potato::detail
