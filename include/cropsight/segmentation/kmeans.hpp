#pragma once
// k-means (Lloyd, k-means++ seeding) of 3D points: a baseline to the seedling GMM.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace cropsight::segmentation {

struct KMeansConfig {
  int clusters = 10;         ///< k
  int max_iterations = 100;  ///< Lloyd iterations at most
  double tolerance = 1e-7;   ///< m; stop when no centre moves more than this
  std::uint32_t seed = 1;    ///< k-means++ seeding

  template <class V>
  void visit(V& v) {
    v("clusters", clusters, "number of clusters k (paper's GMM: 10 components)");
    v("max_iterations", max_iterations, "Lloyd iterations at most");
    v("tolerance", tolerance, "m; largest centre move that ends the iterations");
    v("seed", seed, "random seed of the k-means++ seeding");
  }
};

struct HardClustering {
  std::vector<Eigen::Vector3d> centres;
  std::vector<int> labels;  ///< cluster per point
  double inertia = 0;       ///< m^2; sum of squared distances to the assigned centres
  int iterations = 0;
};

/// Throws Error(where, ...) when there are fewer points than clusters or clusters < 1.
HardClustering kmeans(const std::vector<Eigen::Vector3f>& points, const KMeansConfig& cfg,
                      const std::string& where = "kmeans");

}  // namespace cropsight::segmentation
