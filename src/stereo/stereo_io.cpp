#include "cropsight/stereo/stereo_io.hpp"

#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cv_convert.hpp"

namespace cropsight::stereo {

namespace fs = std::filesystem;

ColorImage read_color(const fs::path& path) {
  if (!fs::exists(path)) throw Error(path.string(), "file not found");
  cv::Mat m = cv::imread(path.string(), cv::IMREAD_COLOR);
  if (m.empty()) throw Error(path.string(), "cannot decode image");
  cv::Mat rgb;
  cv::cvtColor(m, rgb, cv::COLOR_BGR2RGB);
  return detail::to_color(rgb);
}

GrayImage read_gray(const fs::path& path) {
  if (!fs::exists(path)) throw Error(path.string(), "file not found");
  cv::Mat m = cv::imread(path.string(), cv::IMREAD_GRAYSCALE);
  if (m.empty()) throw Error(path.string(), "cannot decode image");
  return detail::to_gray(m);
}

DisparityImage read_disparity(const fs::path& path, double scale) {
  if (!fs::exists(path)) throw Error(path.string(), "file not found");
  cv::Mat m = cv::imread(path.string(), cv::IMREAD_ANYDEPTH | cv::IMREAD_GRAYSCALE);
  if (m.empty()) throw Error(path.string(), "cannot decode disparity image");
  if (m.channels() != 1) throw Error(path.string(), "disparity image must have one channel");
  cv::Mat f;
  m.convertTo(f, CV_32F);
  DisparityImage out(f.cols, f.rows);
  for (int y = 0; y < f.rows; ++y)
    for (int x = 0; x < f.cols; ++x) {
      const float v = f.at<float>(y, x);
      out.at(x, y) = v > 0 ? float(v / scale) : std::nanf("");
    }
  return out;
}

void write_disparity_png(const fs::path& path, const DisparityImage& d, double scale) {
  cv::Mat m(d.height, d.width, CV_16U);
  for (int y = 0; y < d.height; ++y)
    for (int x = 0; x < d.width; ++x) {
      const float v = d.at(x, y);
      m.at<std::uint16_t>(y, x) =
          std::isnan(v) || v <= 0 ? 0 : std::uint16_t(std::min(65535.0, std::round(double(v) * scale)));
    }
  io::write_atomic_with(path, [&](const fs::path& tmp) {
    if (!cv::imwrite(tmp.string(), m)) throw Error(path.string(), "cannot write image");
  });
}

void write_color_png(const fs::path& path, const ColorImage& image) {
  cv::Mat bgr;
  cv::cvtColor(detail::view(image), bgr, cv::COLOR_RGB2BGR);
  io::write_atomic_with(path, [&](const fs::path& tmp) {
    if (!cv::imwrite(tmp.string(), bgr)) throw Error(path.string(), "cannot write image");
  });
}

void write_gray_png(const fs::path& path, const GrayImage& image) {
  io::write_atomic_with(path, [&](const fs::path& tmp) {
    if (!cv::imwrite(tmp.string(), detail::view(image))) throw Error(path.string(), "cannot write image");
  });
}

}  // namespace cropsight::stereo
