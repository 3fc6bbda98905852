#include "cropsight/pipeline/seedling/top_view.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "stereo/cv_convert.hpp"

namespace cropsight::pipeline::seedling {

double TopViewMask::area() const {
  long n = 0;
  for (auto v : mask.data) n += v > 0;
  return double(n) * cell * cell;
}

TopViewMask rasterize_top_view(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& n, double cell,
                               const Eigen::Vector2d& origin, int width, int height) {
  TopViewMask t;
  t.cell = cell;
  t.origin = origin;
  t.mask = GrayImage(width, height, 0);
  const Eigen::Vector3d e1 = n.unitOrthogonal(), e2 = n.cross(e1);
  for (const auto& p : points) {
    const int i = int(std::floor((e1.dot(p) - origin.x()) / cell));
    const int j = int(std::floor((e2.dot(p) - origin.y()) / cell));
    if (i >= 0 && j >= 0 && i < width && j < height) t.mask.at(i, j) = 255;
  }
  // Closing fills the one-cell gaps between the points of a leaf seen at a slant.
  cv::Mat m = stereo::detail::view(t.mask);
  cv::morphologyEx(m, m, cv::MORPH_CLOSE, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(3, 3)));
  return t;
}

}  // namespace cropsight::pipeline::seedling
