#include "cropsight/stereo/seedling_eval.hpp"

#include <cmath>

#include "cropsight/stereo/reconstruct.hpp"

namespace cropsight::stereo {

SeedlingScore score_seedling(const SeedlingDetection& det, const DisparityImage& true_disparity,
                             const GrayImage& true_mask, const RectifiedGeometry& geo, const Eigen::Vector3d& n,
                             double d, const EnvelopeBox& true_envelope, double cell) {
  SeedlingScore s;
  DisparityImage masked = true_disparity;
  for (std::size_t i = 0; i < masked.size(); ++i)
    if (!true_mask.data[i]) masked.data[i] = std::nanf("");
  const StereoPoints truth = reconstruct(masked, geo);
  std::vector<Eigen::Vector3d> tp, dp;
  for (const auto& p : truth.points) tp.push_back(p.cast<double>());
  for (const auto& p : det.points) dp.push_back(p.cast<double>());
  if (true_envelope.volume() > 0) s.volume_ratio = det.envelope.volume() / true_envelope.volume();
  if (tp.empty()) return s;
  const Eigen::Vector3d e1 = n.unitOrthogonal(), e2 = n.cross(e1);
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const auto* set : {&tp, &dp})
    for (const auto& p : *set) {
      const Eigen::Vector2d q(e1.dot(p), e2.dot(p));
      lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
    }
  const Eigen::Vector2d origin = lo - Eigen::Vector2d::Constant(2 * cell);
  const int w = int((hi.x() - lo.x()) / cell) + 5, h = int((hi.y() - lo.y()) / cell) + 5;
  if (double(w) * h > 4e7) {  // detection far from the truth: no overlap worth rasterising
    s.iou = s.sensitivity = 0;
    return s;
  }
  const TopViewMask a = rasterize_top_view(tp, n, cell, origin, w, h);
  const TopViewMask b = rasterize_top_view(dp, n, cell, origin, w, h);
  long inter = 0, uni = 0, area = 0;
  for (std::size_t i = 0; i < a.mask.size(); ++i) {
    const bool x = a.mask.data[i], y = b.mask.data[i];
    inter += x && y;
    uni += x || y;
    area += x;
  }
  s.iou = uni ? double(inter) / double(uni) : 0;
  s.sensitivity = area ? double(inter) / double(area) : 0;
  s.recognised = s.iou >= 0.5;
  return s;
}

}  // namespace cropsight::stereo
