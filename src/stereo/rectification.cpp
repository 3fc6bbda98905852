#include "cropsight/stereo/rectification.hpp"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <utility>

#include "cropsight/core/error.hpp"
#include "cv_convert.hpp"

namespace cropsight::stereo {

struct StereoRectifier::Impl {
  cv::Mat map1x, map1y, map2x, map2y;
  RectifiedGeometry geo;
};

namespace {
cv::Mat to_cv(const Eigen::Matrix3d& m) {
  cv::Mat c(3, 3, CV_64F);
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) c.at<double>(r, k) = m(r, k);
  return c;
}
cv::Mat to_cv(const std::vector<double>& v) {
  cv::Mat c(1, int(v.size()), CV_64F);
  for (int i = 0; i < int(v.size()); ++i) c.at<double>(i) = v[i];
  return c;
}
}  // namespace

StereoRectifier::StereoRectifier(const StereoCalibration& c, double alpha) : impl_(std::make_unique<Impl>()) {
  const cv::Size size(c.width, c.height);
  cv::Mat k1 = to_cv(c.K1), k2 = to_cv(c.K2), d1 = to_cv(c.D1), d2 = to_cv(c.D2), R = to_cv(c.R);
  cv::Mat T = (cv::Mat_<double>(3, 1) << c.T.x(), c.T.y(), c.T.z());
  cv::Mat R1, R2, P1, P2, Q;
  // CALIB_ZERO_DISPARITY: both principal points equal, so disparity = x_left - x_right.
  cv::stereoRectify(k1, d1, k2, d2, size, R, T, R1, R2, P1, P2, Q, cv::CALIB_ZERO_DISPARITY, alpha, size);
  cv::initUndistortRectifyMap(k1, d1, R1, P1, size, CV_32FC1, impl_->map1x, impl_->map1y);
  cv::initUndistortRectifyMap(k2, d2, R2, P2, size, CV_32FC1, impl_->map2x, impl_->map2y);
  RectifiedGeometry& g = impl_->geo;
  g.width = c.width;
  g.height = c.height;
  g.f = P1.at<double>(0, 0);
  g.cx = P1.at<double>(0, 2);
  g.cy = P1.at<double>(1, 2);
  g.cx_right = P2.at<double>(0, 2);
  g.baseline = std::abs(P2.at<double>(0, 3) / P2.at<double>(0, 0));
}

StereoRectifier::~StereoRectifier() = default;
StereoRectifier::StereoRectifier(StereoRectifier&&) noexcept = default;
StereoRectifier& StereoRectifier::operator=(StereoRectifier&&) noexcept = default;

std::pair<ColorImage, ColorImage> StereoRectifier::rectify(const ColorImage& left, const ColorImage& right,
                                                           const std::string& where) const {
  const RectifiedGeometry& g = impl_->geo;
  if (left.width != g.width || left.height != g.height || right.width != g.width || right.height != g.height)
    throw Error(where, "image size differs from the calibration (" + std::to_string(g.width) + "x" +
                           std::to_string(g.height) + ")");
  cv::Mat l, r;
  cv::remap(detail::view(left), l, impl_->map1x, impl_->map1y, cv::INTER_LINEAR, cv::BORDER_CONSTANT);
  cv::remap(detail::view(right), r, impl_->map2x, impl_->map2y, cv::INTER_LINEAR, cv::BORDER_CONSTANT);
  return {detail::to_color(l), detail::to_color(r)};
}

const RectifiedGeometry& StereoRectifier::geometry() const { return impl_->geo; }

bool is_rectified(const StereoCalibration& c) {
  auto zero = [](const std::vector<double>& d) {
    for (double v : d)
      if (std::abs(v) > 1e-12) return false;
    return true;
  };
  return zero(c.D1) && zero(c.D2) && (c.R - Eigen::Matrix3d::Identity()).norm() < 1e-9 && std::abs(c.T.y()) < 1e-9 &&
         std::abs(c.T.z()) < 1e-9 && c.T.x() < 0 && (c.K1 - c.K2).norm() < 1e-9 &&
         std::abs(c.K1(0, 0) - c.K1(1, 1)) < 1e-9;
}

RectifiedGeometry rectified_geometry(const StereoCalibration& c) {
  if (!is_rectified(c)) return StereoRectifier(c).geometry();
  RectifiedGeometry g;
  g.width = c.width;
  g.height = c.height;
  g.f = c.K1(0, 0);
  g.cx = g.cx_right = c.K1(0, 2);
  g.cy = c.K1(1, 2);
  g.baseline = c.baseline();
  return g;
}

RectifiedPair rectify_pair(const StereoCalibration& calib, ColorImage left, ColorImage right,
                           const std::string& where) {
  if (left.width != calib.width || left.height != calib.height)
    throw Error(where, "image size differs from the calibration");
  if (is_rectified(calib)) return {std::move(left), std::move(right), rectified_geometry(calib)};
  StereoRectifier rect(calib);
  auto [l, r] = rect.rectify(left, right, where);
  return {std::move(l), std::move(r), rect.geometry()};
}

}  // namespace cropsight::stereo
