// Colour model fit: Lab conversion by OpenCV, moments by geometry/pca (one covariance code).
#include "cropsight/pipeline/potato/colour_fit.hpp"

#include <opencv2/imgproc.hpp>

#include "cropsight/core/error.hpp"
#include "cropsight/geometry/pca.hpp"
#include "stereo/cv_convert.hpp"

namespace cropsight::pipeline::potato {

void ColourFit::apply_to(BlobConfig& cfg) const {
  cfg.mean_a = mean_a;
  cfg.mean_b = mean_b;
  cfg.cov_aa = cov_aa;
  cfg.cov_ab = cov_ab;
  cfg.cov_bb = cov_bb;
}

ColourFit fit_potato_colour(const std::vector<const ColorImage*>& images,
                            const std::vector<std::vector<Detection2D>>& boxes, double inner_fraction) {
  if (images.size() != boxes.size()) throw Error("colour fit", "one box list per image expected");
  std::vector<Eigen::Vector2d> ab;
  cv::Mat lab, inner;
  for (std::size_t i = 0; i < images.size(); ++i) {
    cv::cvtColor(stereo::detail::view(*images[i]), lab, cv::COLOR_RGB2Lab);
    inner = cv::Mat::zeros(lab.size(), CV_8UC1);
    for (const Detection2D& b : boxes[i]) {
      const cv::Size axes(int(0.5 * inner_fraction * b.width()), int(0.5 * inner_fraction * b.height()));
      if (axes.width > 0 && axes.height > 0)
        cv::ellipse(inner, cv::Point(int(b.centre_x()), int(b.centre_y())), axes, 0, 0, 360, 255, cv::FILLED);
    }
    for (int v = 0; v < lab.rows; ++v)
      for (int u = 0; u < lab.cols; ++u)
        if (inner.at<std::uint8_t>(v, u)) {
          const cv::Vec3b p = lab.at<cv::Vec3b>(v, u);
          ab.emplace_back(p[1], p[2]);
        }
  }
  if (ab.empty()) throw Error("colour fit", "no pixel inside the boxes");
  const auto m = geometry::point_moments(ab.size(), [&](std::size_t k) { return ab[k]; });
  const Eigen::Matrix2d c = m.covariance();
  return {m.mean.x(), m.mean.y(), c(0, 0), c(0, 1), c(1, 1), std::int64_t(ab.size())};
}

}  // namespace cropsight::pipeline::potato
