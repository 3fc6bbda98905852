#include "cropsight/pipeline/potato/overlay.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "stereo/cv_convert.hpp"

namespace cropsight::pipeline::potato {

void draw_detections(ColorImage& img, const std::vector<Detection2D>& dets,
                     const std::vector<std::optional<double>>& angles_rad) {
  cv::Mat m = stereo::detail::view(img);  // a view: drawing writes into img
  for (std::size_t i = 0; i < dets.size(); ++i) {
    const Detection2D& d = dets[i];
    const cv::Point a(int(d.x1), int(d.y1)), b(int(d.x2) - 1, int(d.y2) - 1);
    cv::rectangle(m, a, b, cv::Scalar(0, 255, 0), 2);
    char text[16];
    std::snprintf(text, sizeof text, "%.2f", double(d.score));
    cv::putText(m, text, {a.x, std::max(12, a.y - 3)}, cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(255, 255, 0), 1);
    if (i >= angles_rad.size() || !angles_rad[i]) continue;
    // Half the box's longer side along the axis; image y points down, so the angle's sine flips.
    const double half = 0.5 * std::max(d.x2 - d.x1, d.y2 - d.y1);
    const double cx = 0.5 * (d.x1 + d.x2), cy = 0.5 * (d.y1 + d.y2);
    const double dx = half * std::cos(*angles_rad[i]), dy = -half * std::sin(*angles_rad[i]);
    cv::line(m, cv::Point(int(cx - dx), int(cy - dy)), cv::Point(int(cx + dx), int(cy + dy)), cv::Scalar(255, 0, 0), 2);
  }
}

}  // namespace cropsight::pipeline::potato
