// KNN-PCA normals on a nanoflann k-d tree. Written here (rather than pcl::NormalEstimation) so
// that the eigenvalues, which the grape GBDT uses as shape features, come from the same pass;
// tests/geometry/test_knn_normals.cpp checks the normals against PCL's on the same input.
#include "cropsight/geometry/knn_normals.hpp"

#include <nanoflann.hpp>

#include "cropsight/core/error.hpp"
#include "cropsight/geometry/pca.hpp"

namespace cropsight::geometry {

namespace {
struct Adaptor {
  const std::vector<Eigen::Vector3f>* pts;
  std::size_t kdtree_get_point_count() const { return pts->size(); }
  float kdtree_get_pt(std::size_t i, std::size_t d) const { return (*pts)[i][int(d)]; }
  template <class BBox>
  bool kdtree_get_bbox(BBox&) const {
    return false;
  }
};
using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Adaptor>, Adaptor, 3, std::size_t>;
}  // namespace

struct PointIndex::Impl {
  Adaptor adaptor;
  Tree tree;
  explicit Impl(const std::vector<Eigen::Vector3f>& p)
      : adaptor{&p}, tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {
    tree.buildIndex();
  }
};

PointIndex::PointIndex(const std::vector<Eigen::Vector3f>& points) : impl_(std::make_unique<Impl>(points)) {}
PointIndex::~PointIndex() = default;
std::size_t PointIndex::size() const { return impl_->adaptor.pts->size(); }

void PointIndex::knn(const Eigen::Vector3f& q, int k, std::vector<int>& out, std::vector<float>* sq_dists) const {
  const std::size_t n = std::min<std::size_t>(std::size_t(std::max(k, 0)), size());
  std::vector<std::size_t> idx(n);
  std::vector<float> d(n);
  const std::size_t found = n ? impl_->tree.knnSearch(q.data(), n, idx.data(), d.data()) : 0;
  out.resize(found);
  for (std::size_t i = 0; i < found; ++i) out[i] = int(idx[i]);
  if (sq_dists) sq_dists->assign(d.begin(), d.begin() + long(found));
}

void PointIndex::radius(const Eigen::Vector3f& q, float r, std::vector<int>& out) const {
  std::vector<std::pair<std::size_t, float>> hits;
  impl_->tree.radiusSearch(q.data(), r * r, hits, nanoflann::SearchParams(32, 0.f, false));
  out.resize(hits.size());
  for (std::size_t i = 0; i < hits.size(); ++i) out[i] = int(hits[i].first);
}

int PointIndex::nearest(const Eigen::Vector3f& q) const {
  std::size_t idx = 0;
  float d = 0;
  impl_->tree.knnSearch(q.data(), 1, &idx, &d);
  return int(idx);
}

KnnPcaResult knn_pca(const std::vector<Eigen::Vector3f>& points, const KnnNormalsConfig& cfg) {
  if (cfg.k < 3) throw Error("knn normals", "k must be at least 3, got " + std::to_string(cfg.k));
  KnnPcaResult r;
  const std::size_t n = points.size();
  r.normals.resize(n);
  r.eigenvalues.resize(n);
  if (n == 0) return r;
  PointIndex index(points);
  std::vector<int> nb;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3f& p = points[i];
    index.knn(p, cfg.k, nb);
    Eigen::Vector3f to_view = cfg.viewpoint - p;
    if (nb.size() < 3) {
      const float len = to_view.norm();
      r.normals[i] = len > 0 ? Eigen::Vector3f(to_view / len) : Eigen::Vector3f::UnitZ();
      r.eigenvalues[i].setZero();
      continue;
    }
    // Covariance in double around the neighbourhood mean (float loses precision for clouds far
    // from the origin, e.g. metres at 1-3 m depth with millimetre spacing); closed-form solve.
    const auto pc = pca(
        nb.size(), [&](std::size_t q) { return points[std::size_t(nb[q])].cast<double>(); }, EigenMethod::closed_form);
    Eigen::Vector3f nrm = pc.normal().cast<float>().normalized();
    if (nrm.dot(to_view) < 0) nrm = -nrm;
    r.normals[i] = nrm;
    r.eigenvalues[i] = pc.eigenvalues.cwiseMax(0.0).cast<float>();
  }
  return r;
}

std::vector<Eigen::Vector3f> knn_normals(const std::vector<Eigen::Vector3f>& points, const KnnNormalsConfig& cfg) {
  return knn_pca(points, cfg).normals;
}

std::pair<Eigen::Vector3f, float> normalize_unit_sphere(std::vector<Eigen::Vector3f>& points) {
  if (points.empty()) return {Eigen::Vector3f::Zero(), 1.f};
  const Eigen::Vector3f centroid = point_mean(points).cast<float>();
  float m = 0;
  for (auto& p : points) {
    p -= centroid;
    m = std::max(m, p.norm());
  }
  const float scale = m > 0 ? m : 1.f;
  for (auto& p : points) p /= scale;
  return {centroid, scale};
}

}  // namespace cropsight::geometry
