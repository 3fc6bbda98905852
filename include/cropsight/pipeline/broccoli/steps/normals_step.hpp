#pragma once
// Integral-image normals of the broccoli detector's cloud (StageTimer "normals";
// geometry/integral_normals.hpp for the method). Unit normals in the camera frame, NaN where
// undefined. Lazy normals: OES segments without normals (unless crease edges need the curvature),
// so they are computed after the clustering and only for the pixels of the kept segments, the
// only ones the features read; the cloud then has NaN normals elsewhere. The estimator's integral
// images are reused from frame to frame.
#include <span>

#include "cropsight/core/organized_cloud.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/geometry/integral_normals.hpp"

namespace cropsight::pipeline::broccoli::steps {

class NormalsStep {
 public:
  NormalsStep(geometry::IntegralNormalConfig cfg, bool lazy) : estimator_(cfg), lazy_(lazy) {}

  /// Every pixel's normal, unless the normals are lazy.
  void before_clustering(OrganizedCloud& cloud, StageTimer& timer) {
    if (!lazy_) compute(cloud, {}, timer);
  }
  /// Lazy normals: those of the pixels with owners[i] >= 0 (all pixels when `owners` is empty).
  void after_clustering(OrganizedCloud& cloud, std::span<const int> owners, StageTimer& timer) {
    if (lazy_) compute(cloud, owners, timer);
  }

 private:
  void compute(OrganizedCloud& cloud, std::span<const int> select, StageTimer& timer) {
    auto t = timer.scope("normals");
    estimator_.compute(cloud, select);
  }

  geometry::IntegralNormalEstimator estimator_;
  bool lazy_;
};

}  // namespace cropsight::pipeline::broccoli::steps
