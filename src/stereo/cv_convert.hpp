#pragma once
// Internal: zero-copy views and copies between cropsight images and cv::Mat (stereo module only).
#include <opencv2/core.hpp>

#include "cropsight/core/image.hpp"

namespace cropsight::stereo::detail {

inline cv::Mat view(const ColorImage& im) {
  return cv::Mat(im.height, im.width, CV_8UC3, const_cast<Rgb8*>(im.data.data()));
}
inline cv::Mat view(const GrayImage& im) {
  return cv::Mat(im.height, im.width, CV_8UC1, const_cast<std::uint8_t*>(im.data.data()));
}
inline cv::Mat view(const Image<float>& im) {
  return cv::Mat(im.height, im.width, CV_32FC1, const_cast<float*>(im.data.data()));
}
inline ColorImage to_color(const cv::Mat& m) {  // expects CV_8UC3 in r,g,b order
  ColorImage out(m.cols, m.rows);
  cv::Mat dst = view(out);
  m.copyTo(dst);
  return out;
}
inline GrayImage to_gray(const cv::Mat& m) {
  GrayImage out(m.cols, m.rows);
  cv::Mat dst = view(out);
  m.copyTo(dst);
  return out;
}

}  // namespace cropsight::stereo::detail
