// measure/orientation: the three segmentations of the widened box (see the public header for the
// rules; here, how they are carried out).
#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "measure/orientation_steps.hpp"

namespace cropsight::measure::detail {

cv::Mat border_mask(int rows, int cols, int width) {
  cv::Mat b(rows, cols, CV_8UC1, cv::Scalar(255));
  const int w = std::min(width, std::min(rows, cols) / 2);
  if (rows - 2 * w > 0 && cols - 2 * w > 0) b(cv::Rect(w, w, cols - 2 * w, rows - 2 * w)).setTo(0);
  return b;
}

namespace {

// The largest outer contour of a binary image, filled (holes and all); empty mask when none.
cv::Mat fill_largest_contour(const cv::Mat& binary) {
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(binary.clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
  cv::Mat out = cv::Mat::zeros(binary.size(), CV_8UC1);
  int best = -1;
  double best_area = 0;
  for (int i = 0; i < int(contours.size()); ++i)
    if (const double a = cv::contourArea(contours[i]); a > best_area) best_area = a, best = i;
  if (best >= 0) cv::drawContours(out, contours, best, cv::Scalar(255), cv::FILLED);
  return out;
}

// Otsu's threshold of the values of `img` (CV_8UC1) where `valid` is set.
double otsu_threshold(const cv::Mat& img, const cv::Mat& valid) {
  std::vector<std::uint8_t> values;
  values.reserve(img.total());
  for (int v = 0; v < img.rows; ++v)
    for (int u = 0; u < img.cols; ++u)
      if (valid.at<std::uint8_t>(v, u)) values.push_back(img.at<std::uint8_t>(v, u));
  if (values.empty()) return 255;
  cv::Mat row(1, int(values.size()), CV_8UC1, values.data()), dummy;
  return cv::threshold(row, dummy, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
}

std::uint8_t median_of(std::vector<std::uint8_t>& v) {
  if (v.empty()) return 128;
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// Maps the grey levels of `grey` linearly so that its `percent` darkest pixels go to 0 and its
// `percent` brightest to 255: Canny's thresholds are gradients in grey levels, and a dim shot
// (the shared RGB board is ~130 of 255) has half the gradients of a bright one.
void stretch_contrast(cv::Mat& grey, double percent) {
  int hist[256] = {};
  for (int v = 0; v < grey.rows; ++v) {
    const std::uint8_t* row = grey.ptr<std::uint8_t>(v);
    for (int u = 0; u < grey.cols; ++u) ++hist[row[u]];
  }
  const double n = double(grey.total()), cut = n * percent / 100.0;
  int lo = 0, hi = 255;
  for (double acc = 0; lo < 255 && (acc += hist[lo]) <= cut;) ++lo;
  for (double acc = 0; hi > 0 && (acc += hist[hi]) <= cut;) --hi;
  if (hi <= lo) return;
  grey.convertTo(grey, CV_8U, 255.0 / (hi - lo), -255.0 * lo / (hi - lo));
}

}  // namespace

// `part_fraction` > 0: also the other components that lie mostly inside `inner` (the detector's box
// in the mask's frame) and hold at least that fraction of the central one's pixels, each filled.
cv::Mat component_nearest_centre(const cv::Mat& mask, double part_fraction = 0, cv::Rect inner = {}) {
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  if (n <= 1) return cv::Mat::zeros(mask.size(), CV_8UC1);
  const double cu = 0.5 * mask.cols, cv_ = 0.5 * mask.rows;
  std::vector<double> nearest(std::size_t(n), std::numeric_limits<double>::infinity());
  for (int v = 0; v < mask.rows; ++v) {
    const int* row = labels.ptr<int>(v);
    for (int u = 0; u < mask.cols; ++u)
      if (row[u] > 0) {
        const double d = (u + 0.5 - cu) * (u + 0.5 - cu) + (v + 0.5 - cv_) * (v + 0.5 - cv_);
        nearest[std::size_t(row[u])] = std::min(nearest[std::size_t(row[u])], d);
      }
  }
  int best = 1;
  for (int k = 2; k < n; ++k)
    if (nearest[std::size_t(k)] < nearest[std::size_t(best)] ||
        (nearest[std::size_t(k)] == nearest[std::size_t(best)] &&
         stats.at<int>(k, cv::CC_STAT_AREA) > stats.at<int>(best, cv::CC_STAT_AREA)))
      best = k;
  cv::Mat out = fill_largest_contour(labels == best);
  if (part_fraction <= 0) return out;
  const double central = stats.at<int>(best, cv::CC_STAT_AREA);
  for (int k = 1; k < n; ++k) {
    const int area = stats.at<int>(k, cv::CC_STAT_AREA);
    if (k == best || area < part_fraction * central) continue;
    const cv::Mat part = labels == k;
    if (cv::countNonZero(part(inner & cv::Rect(0, 0, mask.cols, mask.rows))) < 0.8 * area) continue;
    out |= fill_largest_contour(part);
  }
  return out;
}

cv::Mat segment_canny(const cv::Mat& rgb, const OrientationConfig& cfg) {
  cv::Mat grey, smooth, edges;
  cv::cvtColor(rgb, grey, cv::COLOR_RGB2GRAY);
  // RGB only: the colour map of a depth image spans its full range by construction.
  if (cfg.input == OrientationInput::rgb && cfg.canny_stretch_percent > 0)
    stretch_contrast(grey, cfg.canny_stretch_percent);
  cv::bilateralFilter(grey, smooth, cfg.bilateral_diameter, cfg.bilateral_sigma_color, cfg.bilateral_sigma_space);
  cv::Canny(smooth, edges, cfg.canny_low, cfg.canny_high);
  if (cfg.canny_close_iterations > 0)
    cv::dilate(edges, edges, cv::Mat(), cv::Point(-1, -1), cfg.canny_close_iterations);
  return fill_largest_contour(edges);
}

cv::Mat segment_kmeans(const cv::Mat& rgb, const OrientationConfig& cfg) {
  cv::Mat samples;
  rgb.reshape(1, int(rgb.total())).convertTo(samples, CV_32F);
  cv::Mat labels, centres;
  cv::theRNG().state = std::uint64_t(cfg.kmeans_seed) + 1;  // OpenCV's RNG refuses state 0
  cv::kmeans(
      samples, 2, labels,
      cv::TermCriteria(cv::TermCriteria::EPS | cv::TermCriteria::COUNT, cfg.kmeans_max_iterations, cfg.kmeans_epsilon),
      cfg.kmeans_attempts, cv::KMEANS_PP_CENTERS, centres);
  const cv::Mat border = border_mask(rgb.rows, rgb.cols, cfg.border_px);
  const int* lab = labels.ptr<int>(0);
  std::size_t on_border[2] = {0, 0};
  for (int i = 0; i < int(rgb.total()); ++i)
    if (border.data[i]) ++on_border[lab[i] & 1];
  const int potato = on_border[1] < on_border[0] ? 1 : 0;
  cv::Mat mask(rgb.rows, rgb.cols, CV_8UC1);
  for (int i = 0; i < int(rgb.total()); ++i) mask.data[i] = lab[i] == potato ? 255 : 0;
  return mask;
}

// Long on purpose: one segmentation in order: the threshold (depth hue or chroma), the string closing, the no-depth
// fill.
cv::Mat segment_ours(const cv::Mat& rgb, const OrientationConfig& cfg) {
  cv::Mat score(rgb.rows, rgb.cols, CV_8UC1), valid(rgb.rows, rgb.cols, CV_8UC1, cv::Scalar(255));
  if (cfg.input == OrientationInput::depth) {
    // Nearness from the colour map's hue: OpenCV hue 0 (red, near) … 120 (blue, far); hues past
    // 150 (magenta) only arise at the dark red end. Black = no depth: background, and left out of
    // the threshold.
    cv::Mat hsv;
    cv::cvtColor(rgb, hsv, cv::COLOR_RGB2HSV);
    for (int i = 0; i < int(rgb.total()); ++i) {
      const std::uint8_t* p = hsv.data + 3 * i;
      if (p[2] < cfg.ours_black_value) {
        score.data[i] = 0;
        valid.data[i] = 0;
        continue;
      }
      const int h = p[0] > 150 ? 0 : std::min<int>(p[0], 120);
      score.data[i] = std::uint8_t((120 - h) * 255 / 120);
    }
  } else {
    // Chroma distance from the border's median a*, b*: white and grey (shadowed) board alike are
    // near it; the potato's yellow-brown is far.
    cv::Mat lab;
    cv::cvtColor(rgb, lab, cv::COLOR_RGB2Lab);
    const cv::Mat border = border_mask(rgb.rows, rgb.cols, cfg.border_px);
    std::vector<std::uint8_t> as, bs;
    for (int i = 0; i < int(rgb.total()); ++i)
      if (border.data[i]) as.push_back(lab.data[3 * i + 1]), bs.push_back(lab.data[3 * i + 2]);
    const int a0 = median_of(as), b0 = median_of(bs);
    for (int i = 0; i < int(rgb.total()); ++i) {
      const double da = lab.data[3 * i + 1] - a0, db = lab.data[3 * i + 2] - b0;
      score.data[i] = cv::saturate_cast<std::uint8_t>(4.0 * std::sqrt(da * da + db * db));
    }
  }
  const double t = otsu_threshold(score, valid);
  cv::Mat mask = (score > t) & valid;
  const double box_side = std::min(rgb.rows, rgb.cols) / (1.0 + 2.0 * cfg.box_margin);
  // A string across the potato cuts a gap as wide as the string into the mask (RGB: the string's
  // colour; depth: its no-depth shadow): a closing wider than a string bridges it, before the
  // opening removes the strings outside the potato.
  // RGB only: on colourised depth a string is no depth (black), background already, and a closing
  // would join the near blobs of strings above the potato to it.
  const double closing = cfg.input == OrientationInput::rgb ? cfg.ours_closing_fraction : 0.0;
  const int kc = std::max(1, int(std::lround(closing * box_side)) | 1);
  if (kc > 1) cv::morphologyEx(mask, mask, cv::MORPH_CLOSE, cv::getStructuringElement(cv::MORPH_ELLIPSE, {kc, kc}));
  const int k = std::max(1, int(std::lround(cfg.ours_opening_fraction * box_side)) | 1);
  if (k > 1) cv::morphologyEx(mask, mask, cv::MORPH_OPEN, cv::getStructuringElement(cv::MORPH_ELLIPSE, {k, k}));
  // The detector's box inside the widened one (the margin on each side).
  const int mx = int(std::lround(rgb.cols * cfg.box_margin / (1.0 + 2.0 * cfg.box_margin))),
            my = int(std::lround(rgb.rows * cfg.box_margin / (1.0 + 2.0 * cfg.box_margin)));
  const cv::Rect inner(mx, my, rgb.cols - 2 * mx, rgb.rows - 2 * my);
  cv::Mat potato = component_nearest_centre(mask, cfg.ours_part_fraction, inner);
  if (cfg.input != OrientationInput::depth || !(cfg.ours_no_depth_fill_fraction > 0) || potato.empty()) return potato;
  // No-depth pixels inside the detector's box that touch the potato are potato the sensor missed
  // (a string's shadow, a dim or grazing patch): the box comes from the RGB image, which sees it.
  // An opening first keeps only the wide no-depth patches: strings, and the D415's shadow band
  // beside a near object, are thin, and joining them would tilt the axis.
  cv::Mat no_depth = cv::Mat::zeros(mask.size(), CV_8UC1);
  no_depth(inner).setTo(255, valid(inner) == 0);
  if (cv::countNonZero(no_depth) == 0) return potato;
  const int kf = std::max(1, int(std::lround(cfg.ours_no_depth_fill_fraction * box_side)) | 1);
  if (kf > 1) {
    // The opening as its two halves: on most shots nothing survives the erosion, and the rest of
    // the step is skipped.
    const cv::Mat disc = cv::getStructuringElement(cv::MORPH_ELLIPSE, {kf, kf});
    cv::Mat core;
    cv::erode(no_depth, core, disc);
    if (cv::countNonZero(core) == 0) return potato;
    cv::dilate(core, no_depth, disc);
  }
  cv::Mat labels;
  const int n = cv::connectedComponents(no_depth, labels, 8, CV_32S);
  if (n <= 1) return potato;
  cv::Mat near;
  cv::dilate(potato, near, cv::Mat());  // 3x3: the pixels next to the potato
  std::vector<std::uint8_t> touches(std::size_t(n), 0);
  for (int v = 0; v < labels.rows; ++v)
    for (int u = 0; u < labels.cols; ++u)
      if (const int l = labels.at<int>(v, u); l > 0 && near.at<std::uint8_t>(v, u)) touches[std::size_t(l)] = 1;
  // touches[0] (not a no-depth patch) is never set above.
  for (int v = 0; v < labels.rows; ++v)
    for (int u = 0; u < labels.cols; ++u)
      if (touches[std::size_t(labels.at<int>(v, u))]) potato.at<std::uint8_t>(v, u) = 255;
  return fill_largest_contour(potato);
}

}  // namespace cropsight::measure::detail
