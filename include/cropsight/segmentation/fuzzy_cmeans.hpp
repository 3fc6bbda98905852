#pragma once
// Fuzzy c-means (Bezdek 1981) of 3D points: a baseline to the seedling GMM.
// Memberships u_ij = 1 / sum_k (d_ij / d_ik)^(2/(m-1)); centres are u^m-weighted means.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace cropsight::segmentation {

struct FuzzyCMeansConfig {
  int clusters = 10;       ///< c
  double fuzziness = 2.0;  ///< m > 1
  int max_iterations = 100;
  double tolerance = 1e-5;  ///< largest membership change that ends the iterations
  std::uint32_t seed = 1;   ///< k-means++ seeding of the initial centres

  template <class V>
  void visit(V& v) {
    v("clusters", clusters, "number of clusters c");
    v("fuzziness", fuzziness, "fuzzifier m > 1 (usual: 2)");
    v("max_iterations", max_iterations, "iterations at most");
    v("tolerance", tolerance, "largest membership change that ends the iterations");
    v("seed", seed, "random seed of the initial centres");
  }
};

struct FuzzyClustering {
  std::vector<Eigen::Vector3d> centres;
  std::vector<float> memberships;  ///< point-major: memberships[i * c + j], rows sum to 1
  std::vector<int> labels;         ///< cluster of largest membership per point
  int iterations = 0;
};

/// Throws Error(where, ...) when there are fewer points than clusters, clusters < 1 or m <= 1.
FuzzyClustering fuzzy_cmeans(const std::vector<Eigen::Vector3f>& points, const FuzzyCMeansConfig& cfg,
                             const std::string& where = "fuzzy c-means");

}  // namespace cropsight::segmentation
