#include "cropsight/pipeline/potato/potato_overlay.hpp"

#include <algorithm>
#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "stereo/cv_convert.hpp"

namespace cropsight::pipeline::potato {

void draw_detections(ColorImage& img, const std::vector<Detection2D>& dets) {
  cv::Mat m = stereo::detail::view(img);  // a view: drawing writes into img
  for (const Detection2D& d : dets) {
    const cv::Point a(int(d.x1), int(d.y1)), b(int(d.x2) - 1, int(d.y2) - 1);
    cv::rectangle(m, a, b, cv::Scalar(0, 255, 0), 2);
    char text[16];
    std::snprintf(text, sizeof text, "%.2f", double(d.score));
    cv::putText(m, text, {a.x, std::max(12, a.y - 3)}, cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(255, 255, 0), 1);
  }
}

}  // namespace cropsight::pipeline::potato
