// pipeline/potato: the stand-in box source for the orientation images (one potato on a board);
// the rule is in orientation_dataset.hpp.
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "cropsight/core/error.hpp"
#include "cropsight/pipeline/potato/orientation_dataset.hpp"
#include "stereo/cv_convert.hpp"

namespace cropsight::pipeline::potato {

std::vector<Detection2D> BoardBlobDetector::detect(const DetectorInput& in) {
  if (!in.image || in.image->empty()) throw Error("image", "empty image");
  const cv::Mat rgb = stereo::detail::view(*in.image);
  cv::Mat lab;
  cv::cvtColor(rgb, lab, cv::COLOR_RGB2Lab);
  // The board's chroma: the median a*, b* of the whole image.
  int hist_a[256] = {}, hist_b[256] = {};
  for (std::size_t i = 0; i < lab.total(); ++i) ++hist_a[lab.data[3 * i + 1]], ++hist_b[lab.data[3 * i + 2]];
  auto median = [&](const int* h) {
    std::size_t acc = 0;
    for (int k = 0; k < 256; ++k)
      if ((acc += std::size_t(h[k])) * 2 >= lab.total()) return k;
    return 128;
  };
  const int a0 = median(hist_a), b0 = median(hist_b);
  cv::Mat fg(rgb.rows, rgb.cols, CV_8UC1);
  for (std::size_t i = 0; i < lab.total(); ++i) {
    const double da = lab.data[3 * i + 1] - a0, db = lab.data[3 * i + 2] - b0;
    fg.data[i] = std::sqrt(da * da + db * db) > chroma_threshold_ ? 255 : 0;
  }
  // A string crossing the potato cuts its blob in two (a gap as wide as the string): a closing
  // wider than a string bridges it.
  if (closing_px_ > 1)
    cv::morphologyEx(fg, fg, cv::MORPH_CLOSE,
                     cv::getStructuringElement(cv::MORPH_ELLIPSE, {closing_px_ | 1, closing_px_ | 1}));
  if (opening_px_ > 1)
    cv::morphologyEx(fg, fg, cv::MORPH_OPEN,
                     cv::getStructuringElement(cv::MORPH_ELLIPSE, {opening_px_ | 1, opening_px_ | 1}));
  // The potato is the thickest blob: the one holding the largest inscribed disc (strings and their
  // knots are thin, whatever their length). An opening by a disc of half that radius keeps its
  // body and cuts off the strings that still touch it, at any scale; the box is the body grown
  // back by a quarter of the radius inside the foreground (the opening rounds off its ends).
  cv::Mat dist;
  cv::distanceTransform(fg, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  double r = 0;
  cv::Point deepest;
  cv::minMaxLoc(dist, nullptr, &r, nullptr, &deepest);
  if (r < 1) return {};
  const int k = std::max(3, int(std::lround(r)) | 1);
  cv::Mat core;
  cv::morphologyEx(fg, core, cv::MORPH_OPEN, cv::getStructuringElement(cv::MORPH_ELLIPSE, {k, k}));
  if (!core.at<std::uint8_t>(deepest)) core = fg.clone();
  cv::Mat labels;
  cv::connectedComponents(core, labels, 8, CV_32S);
  core = labels == labels.at<int>(deepest);
  const int g = std::max(3, int(std::lround(0.5 * r)) | 1);  // diameter r / 2 = radius r / 4
  cv::dilate(core, core, cv::getStructuringElement(cv::MORPH_ELLIPSE, {g, g}));
  const cv::Rect b = cv::boundingRect(core & fg);
  if (b.empty()) return {};
  return {Detection2D{float(b.x), float(b.y), float(b.x + b.width), float(b.y + b.height), 0, 1.f}};
}

}  // namespace cropsight::pipeline::potato
