#pragma once
// The steps of the seedling pipeline after reconstruction, one function each, in the order
// Pipeline::process() calls them (the rule behind each is documented in
// seedling/pipeline.hpp). They are public so that a step can be tested, timed or replaced alone.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "cropsight/core/image.hpp"
#include "cropsight/pipeline/seedling/config.hpp"
#include "cropsight/pipeline/seedling/top_view.hpp"
#include "cropsight/segmentation/gmm.hpp"
#include "cropsight/stereo/reconstruct.hpp"

namespace cropsight::pipeline::seedling {

/// The soil: n . x + d = 0, n unit and towards the camera (d >= 0), so heights above it are positive.
struct SoilPlane {
  Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  double d = 0;
};

/// RANSAC plane (cfg.ransac_*) on a fixed-seed random subset of `points`, refined by least squares
/// on its inliers. Throws Error(where, ...) for fewer than 3 points.
SoilPlane fit_soil_plane(const std::vector<Eigen::Vector3f>& points, const Config& cfg, const std::string& where);

/// Height of every point above `plane` (single precision, as the rule compares it).
std::vector<float> heights_above(const std::vector<Eigen::Vector3f>& points, const SoilPlane& plane);

/// Plant candidates (indices into `points`): height in (min_height, max_height), then the
/// excess-green test of their left-image pixel (candidate_min_exg > -1), then the image-space
/// opening of their mask (candidate_open > 0).
std::vector<int> select_candidates(const stereo::StereoPoints& points, const std::vector<float>& height,
                                   const ColorImage& left, const Config& cfg);

/// The recognition rule (steps 2-3): the seed component (highest mean height among components of
/// at least min_component_points members), then every component with mean height >= height_ratio x
/// the seed's and a member within join_distance of the chosen ones (seen from above, i.e. the 3D
/// distance with the height difference taken out, when cfg.join_top_view), in the order they joined.
/// Empty when no component is large enough. `height[i]` is the height of `sampled[i]`.
std::vector<int> select_components(const std::vector<Eigen::Vector3f>& sampled, const std::vector<float>& height,
                                   const segmentation::GmmResult& gmm, const Config& cfg);

/// The sampled points whose GMM label is one of `components`, in sampling order.
std::vector<Eigen::Vector3f> points_of_components(const std::vector<Eigen::Vector3f>& sampled,
                                                  const std::vector<int>& labels, const std::vector<int>& components);

/// KNN outlier filter (cfg.outlier); sets of at most mean_k + 1 points are returned unchanged.
std::vector<Eigen::Vector3f> remove_outliers(const std::vector<Eigen::Vector3f>& points, const Config& cfg);

/// Top-view densification (step 5): the candidates whose top-view cell lies within topview_dilate
/// cells of a kept sample, restricted to the largest connected top-view region.
struct DensePlant {
  std::vector<int> indices;  ///< into the reconstructed points, in candidate order
  TopViewMask top_view;      ///< of the dense points, on the grid around the kept samples
};
DensePlant densify_top_view(const std::vector<Eigen::Vector3f>& kept, const stereo::StereoPoints& points,
                            const std::vector<int>& candidates, const SoilPlane& plane, const Config& cfg);

}  // namespace cropsight::pipeline::seedling
