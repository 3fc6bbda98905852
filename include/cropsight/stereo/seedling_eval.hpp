#pragma once
// Scores of one seedling detection against simulator ground truth (issue 5's metrics):
//   top-view IoU and sensitivity (intersection / true area) on the TRUE soil plane, both masks
//   rasterised on one grid (cell 4 mm, 3x3 closing); the true top view is the seedling as the left
//   camera sees it (ground-truth disparity at the ground-truth mask's pixels);
//   volume ratio = detected / true envelope-box volume (true box from the seedling mesh).
#include <Eigen/Core>

#include "cropsight/core/image.hpp"
#include "cropsight/stereo/seedling_detector.hpp"

namespace cropsight::stereo {

struct SeedlingScore {
  double iou = 0;
  double sensitivity = 0;
  double volume_ratio = 0;
  bool recognised = false;  ///< iou >= 0.5
};

SeedlingScore score_seedling(const SeedlingDetection& det, const DisparityImage& true_disparity,
                             const GrayImage& true_mask, const RectifiedGeometry& geometry,
                             const Eigen::Vector3d& true_plane_normal, double true_plane_d,
                             const EnvelopeBox& true_envelope, double cell = 0.004);

}  // namespace cropsight::stereo
