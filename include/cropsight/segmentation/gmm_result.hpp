#pragma once
// A fitted Gaussian mixture and what EM did (fit_gmm, gmm.hpp): plain C++17 data, so that the
// seedling pipeline's results reach the ROS nodes (built as C++17) as they are.
#include <Eigen/Core>
#include <vector>

namespace cropsight::segmentation {

struct GmmModel {
  std::vector<double> weights;               ///< mixing weights, sum 1
  std::vector<Eigen::Vector3d> means;        ///< same frame and units as the points
  std::vector<Eigen::Matrix3d> covariances;  ///< full, symmetric positive definite
  int size() const { return int(weights.size()); }
};

struct GmmResult {
  GmmModel model;
  std::vector<int> labels;    ///< most responsible component per point
  double log_likelihood = 0;  ///< mean log-density per point under the final model
  int iterations = 0;         ///< EM iterations run
  bool converged = false;     ///< tolerance reached before max_iterations
};

}  // namespace cropsight::segmentation
