#pragma once
// KNN-PCA normals (grape pipeline, Luo et al. §2.3: k = 30 nearest neighbours, normal = the
// eigenvector of the neighbourhood covariance with the smallest eigenvalue, oriented towards the
// camera) and the small k-d tree index they are built on (nanoflann, hidden behind a pimpl so
// that this header stays light). Units are those of the input points (metres for camera
// clouds, unit-sphere scale for the dataset's normalised clouds).
#include <Eigen/Core>
#include <memory>
#include <vector>

namespace cropsight::geometry {

/// Exact nearest-neighbour queries over a fixed point set (a k-d tree). The points are
/// referenced, not copied: they must outlive the index and stay unchanged.
class PointIndex {
 public:
  explicit PointIndex(const std::vector<Eigen::Vector3f>& points);
  ~PointIndex();
  PointIndex(const PointIndex&) = delete;
  PointIndex& operator=(const PointIndex&) = delete;

  /// Indices of the k nearest points to `q` (including a point at q itself), nearest first.
  /// Returns min(k, size) indices. `sq_dists` (optional) receives squared distances.
  void knn(const Eigen::Vector3f& q, int k, std::vector<int>& out, std::vector<float>* sq_dists = nullptr) const;
  /// Indices of every point within `radius` of q (unsorted).
  void radius(const Eigen::Vector3f& q, float radius, std::vector<int>& out) const;
  /// Index of the nearest point.
  int nearest(const Eigen::Vector3f& q) const;
  std::size_t size() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Per-point result of local PCA over the k nearest neighbours.
struct KnnPcaResult {
  std::vector<Eigen::Vector3f> normals;      ///< unit, oriented so that dot(n, viewpoint - p) >= 0
  std::vector<Eigen::Vector3f> eigenvalues;  ///< covariance eigenvalues, ascending (λ0 ≤ λ1 ≤ λ2)
};

struct KnnNormalsConfig {
  int k = 30;                                           ///< neighbours per point (paper: 30, Luo et al. §2.3)
  Eigen::Vector3f viewpoint = Eigen::Vector3f::Zero();  ///< camera centre in the cloud's frame

  template <class V>
  void visit(V& v) {
    v("k", k, "count; neighbours of the KNN-PCA normal (paper: 30, Luo et al. 2.3)");
  }
};

/// KNN-PCA normals and eigenvalues of every point. Degenerate neighbourhoods (fewer than 3
/// points) get the normal pointing to the viewpoint and zero eigenvalues.
KnnPcaResult knn_pca(const std::vector<Eigen::Vector3f>& points, const KnnNormalsConfig& cfg = {});

/// Convenience: only the normals.
std::vector<Eigen::Vector3f> knn_normals(const std::vector<Eigen::Vector3f>& points, const KnnNormalsConfig& cfg = {});

/// Centres the points on their centroid and scales them so that the farthest lies on the unit
/// sphere (the network input normalisation of PointNet++ / the grape dataset). Returns the
/// (centroid, scale) used: p_normalised = (p - centroid) / scale.
std::pair<Eigen::Vector3f, float> normalize_unit_sphere(std::vector<Eigen::Vector3f>& points);

}  // namespace cropsight::geometry
