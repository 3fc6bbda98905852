#pragma once
// Gaussian mixture model of 3D points fitted by expectation-maximisation (EM) with full
// covariances: the clustering step of the broccoli-seedling pipeline (paper: K = 10 components on
// 4096 down-sampled points). Initialisation: k-means++ seeds (Arthur & Vassilvitskii 2007), one
// hard assignment for the initial weights / covariances. Convergence: relative change of the
// total log-likelihood below `tolerance`, as cv::ml::EM's EPS criterion.
//
// fit_gmm() is our implementation (single precision, explicit SIMD over points, Cholesky
// factors, log-sum-exp responsibilities); fit_gmm_opencv() runs cv::ml::EM on the same points as
// the reference that tests and benchmarks compare against.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "cropsight/core/config.hpp"
#include "cropsight/segmentation/gmm_result.hpp"

namespace cropsight::segmentation {

/// Largest K accepted: EM costs K x points per iteration, so K beyond a few hundred means nothing.
inline constexpr int kMaxGmmComponents = 256;

struct GmmConfig {
  int components = 10;         ///< K
  int max_iterations = 100;    ///< EM iterations at most
  double tolerance = 1e-4;     ///< stop when |LL_t - LL_{t-1}| < tolerance * |LL_t| (LL summed over points)
  double min_variance = 1e-8;  ///< m^2; ridge added to every covariance diagonal (keeps them invertible)
  std::uint32_t seed = 1;      ///< k-means++ seeding

  template <class V>
  void visit(V& v) {
    v("components", components, "number of Gaussian components K (paper: 10, seedling GMM)",
      Range::within(1, kMaxGmmComponents));
    v("max_iterations", max_iterations, "EM iterations at most (cv::ml::EM default: 100)", Range::within(1, 100000));
    v("tolerance", tolerance, "relative change of the summed log-likelihood that ends EM (paper: not given)",
      Range::within(0, 1));
    v("min_variance", min_variance, "m^2; ridge added to each covariance diagonal", Range::within(0, 1));
    v("seed", seed, "random seed of the k-means++ initialisation");
  }
};

/// Fits a K-component full-covariance GMM. Throws Error(where, ...) when there are fewer points
/// than components, K < 1, or a point is not finite.
GmmResult fit_gmm(const std::vector<Eigen::Vector3f>& points, const GmmConfig& cfg, const std::string& where = "gmm");

/// Initial model from k-means++ seeds and one hard assignment (what fit_gmm starts EM from).
GmmModel gmm_initial_model(const std::vector<Eigen::Vector3f>& points, const GmmConfig& cfg,
                           const std::string& where = "gmm");

/// Same fit with OpenCV's cv::ml::EM (COV_MAT_GENERIC, same K, iterations and tolerance). With
/// `init`, EM starts from that model (trainE); without, from OpenCV's own k-means (trainEM).
GmmResult fit_gmm_opencv(const std::vector<Eigen::Vector3f>& points, const GmmConfig& cfg,
                         const GmmModel* init = nullptr, const std::string& where = "gmm");

/// Mean log-density per point of `points` under `model` (double precision, for checks).
double gmm_mean_log_likelihood(const GmmModel& model, const std::vector<Eigen::Vector3f>& points);

}  // namespace cropsight::segmentation
