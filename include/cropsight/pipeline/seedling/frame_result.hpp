#pragma once
// What the seedling pipeline returns for one rectified pair (Pipeline::process, pipeline.hpp).
// Plain C++17 data, so that the ROS node (built as C++17) uses it as it is. Units: metres, the
// rectified left camera frame (x right, y down, z forward); pixels of the left image.
#include <Eigen/Core>
#include <vector>

#include "cropsight/core/image.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/measure/envelope.hpp"
#include "cropsight/pipeline/seedling/top_view.hpp"
#include "cropsight/segmentation/gmm_result.hpp"

namespace cropsight::pipeline::seedling {

struct FrameResult {
  bool found = false;
  std::vector<Eigen::Vector3f> points;  ///< dense seedling points, rectified left camera frame
  std::vector<int> pixels;              ///< their left-image indices
  GrayImage image_mask;                 ///< left image, 255 = seedling
  TopViewMask top_view;
  measure::EnvelopeBox envelope;
  Eigen::Vector3d plane_normal = Eigen::Vector3d::UnitZ();  ///< soil: n . x + d = 0, n towards the camera
  double plane_d = 0;
  int points_total = 0, points_candidates = 0, points_sampled = 0, points_seedling_sampled = 0;
  segmentation::GmmResult gmm;
  std::vector<Eigen::Vector3f> sampled;  ///< the down-sampled candidates the GMM saw
  std::vector<int> chosen_components;
  StageTimer timer;
  /// Mean of `points` (m, rectified left camera frame); zero when nothing was found.
  Eigen::Vector3d centroid() const {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const auto& p : points) sum += p.cast<double>();
    return points.empty() ? sum : Eigen::Vector3d(sum / double(points.size()));
  }  ///< stages: disparity, reconstruct, plane, sample, gmm, recognise, outlier, output
};

}  // namespace cropsight::pipeline::seedling
