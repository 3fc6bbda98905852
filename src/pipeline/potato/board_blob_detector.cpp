// pipeline/potato: the stand-in box source for the orientation images (one potato on a board).
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
  if (opening_px_ > 1)
    cv::morphologyEx(fg, fg, cv::MORPH_OPEN,
                     cv::getStructuringElement(cv::MORPH_ELLIPSE, {opening_px_ | 1, opening_px_ | 1}));
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(fg, labels, stats, centroids, 8, CV_32S);
  int best = 0;
  for (int k = 1; k < n; ++k)
    if (best == 0 || stats.at<int>(k, cv::CC_STAT_AREA) > stats.at<int>(best, cv::CC_STAT_AREA)) best = k;
  if (best == 0) return {};
  const float x = float(stats.at<int>(best, cv::CC_STAT_LEFT)), y = float(stats.at<int>(best, cv::CC_STAT_TOP));
  return {Detection2D{x, y, x + float(stats.at<int>(best, cv::CC_STAT_WIDTH)),
                      y + float(stats.at<int>(best, cv::CC_STAT_HEIGHT)), 0, 1.f}};
}

}  // namespace cropsight::pipeline::potato
