#pragma once
// Principal component analysis of a point set, written once for every caller (KNN-PCA normals,
// the grape neighbourhood features, the geometric features of a broccoli segment, the head sizer's
// flatness test, the seedling soil plane and envelope box):
//   point_mean() / point_moments(): the mean, and the scatter matrix about it, in double precision
//     and in two passes (the second one centred on the mean: a one-pass sum of p p^T loses the
//     millimetre spread of clouds that lie metres from the origin);
//   principal_axes() / principal_values(): eigenvalues (and unit eigenvectors) of a scatter or
//     covariance matrix;
//   pca(): both, on the covariance.
// Conventions:
//   - eigenvalues ascending (λ0 ≤ λ1 [≤ λ2]); column k of `axes` is the unit eigenvector of
//     eigenvalue k, so axes.col(0) is the normal of the least-squares plane (of the line, in 2D)
//     and axes.col(D - 1) the major axis. Signs are Eigen's (arbitrary): callers orient them.
//   - units: the mean has the units of the points (m for camera clouds), the scatter, covariance
//     and eigenvalues their square; everything is in the points' own frame.
//   - the covariance is the population one (scatter / n).
// The accumulation is a header template over a point accessor, so that the per-point hot loops
// (KNN normals, grape features: one neighbourhood per point of ~100k) stay inlined; the
// eigen-solvers are compiled once, in src/geometry/pca.cpp (2-D and 3-D). Not for translation
// units built for another instruction set (gmm_avx2.cpp): their inline copies would be merged
// with the baseline ones at link time.
#include <Eigen/Core>
#include <cstddef>
#include <type_traits>
#include <vector>

namespace cropsight::geometry {

template <int D>
using PcaVector = Eigen::Matrix<double, D, 1>;
template <int D>
using PcaMatrix = Eigen::Matrix<double, D, D>;

/// The first two moments of `count` points.
template <int D>
struct PointMoments {
  std::size_t count = 0;
  PcaVector<D> mean = PcaVector<D>::Zero();     ///< units of the points (zero when count = 0)
  PcaMatrix<D> scatter = PcaMatrix<D>::Zero();  ///< Σ (p - mean)(p - mean)^T, squared units
  /// Population covariance, scatter / count (count > 0).
  PcaMatrix<D> covariance() const { return scatter / double(count); }
};

/// The point type an accessor returns: `at(i)` yields a double Eigen column vector (a stored
/// vector or an expression of stored data such as `pts[idx[i]].cast<double>()`).
template <class At>
using AccessedPoint = typename std::decay_t<decltype(std::declval<At&>()(std::size_t{0}))>::PlainObject;

/// Mean of the points at(0) … at(n - 1), summed in that order; zero when n = 0.
template <class At>
AccessedPoint<At> point_mean(std::size_t n, At&& at) {
  using P = AccessedPoint<At>;
  static_assert(std::is_same_v<typename P::Scalar, double> && P::ColsAtCompileTime == 1,
                "the accessor must return a double column vector (cast float points)");
  P mean = P::Zero();
  if (n == 0) return mean;
  for (std::size_t i = 0; i < n; ++i) mean += at(i);
  mean /= double(n);
  return mean;
}

/// Scatter Σ (p - mean)(p - mean)^T of the points at(0) … at(n - 1) about `mean` (their mean,
/// from point_mean() or from a caller's own pass that sums other attributes of the same points).
template <class At>
PcaMatrix<AccessedPoint<At>::RowsAtCompileTime> scatter_about(std::size_t n, At&& at, const AccessedPoint<At>& mean) {
  constexpr int D = AccessedPoint<At>::RowsAtCompileTime;
  PcaMatrix<D> scatter = PcaMatrix<D>::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    const PcaVector<D> d = at(i) - mean;
    scatter.noalias() += d * d.transpose();
  }
  return scatter;
}

/// Mean and scatter of the points at(0) … at(n - 1) (at is called twice per point).
template <class At>
PointMoments<AccessedPoint<At>::RowsAtCompileTime> point_moments(std::size_t n, At&& at) {
  const auto mean = point_mean(n, at);
  return {n, mean, scatter_about(n, at, mean)};
}

/// Of a list of points (float points are widened to double first).
template <class S, int D>
PcaVector<D> point_mean(const std::vector<Eigen::Matrix<S, D, 1>>& points) {
  return point_mean(points.size(), [&](std::size_t i) { return points[i].template cast<double>(); });
}
template <class S, int D>
PointMoments<D> point_moments(const std::vector<Eigen::Matrix<S, D, 1>>& points) {
  return point_moments(points.size(), [&](std::size_t i) { return points[i].template cast<double>(); });
}

/// How the symmetric eigenproblem is solved (both are Eigen's SelfAdjointEigenSolver).
enum class EigenMethod {
  iterative,    ///< tridiagonal QR (compute): accurate at any conditioning
  closed_form,  ///< analytic roots (computeDirect): several times faster, but the small
                ///< eigenvalues of an ill-conditioned matrix lose relative accuracy; what the
                ///< per-point normals and features use
};

/// Eigen-decomposition of a symmetric D×D matrix.
template <int D>
struct EigenAxes {
  PcaVector<D> eigenvalues = PcaVector<D>::Zero();        ///< ascending (squared units of a covariance)
  PcaMatrix<D> axes = PcaMatrix<D>::Identity();           ///< column k: unit eigenvector of eigenvalues(k)
  PcaVector<D> normal() const { return axes.col(0); }     ///< smallest axis: plane normal
  PcaVector<D> major() const { return axes.col(D - 1); }  ///< largest axis
};

/// PCA of a point set: the mean and the eigen-decomposition of the covariance about it.
template <int D>
struct Pca : EigenAxes<D> {
  PcaVector<D> mean = PcaVector<D>::Zero();  ///< units of the points
};

/// Eigenvalues and eigenvectors of the symmetric matrix `a` (a scatter or covariance matrix; only
/// the lower triangle is read).
EigenAxes<2> principal_axes(const PcaMatrix<2>& a, EigenMethod method = EigenMethod::iterative);
EigenAxes<3> principal_axes(const PcaMatrix<3>& a, EigenMethod method = EigenMethod::iterative);

/// Eigenvalues only (ascending, iterative method): what a flatness or elongation test needs.
PcaVector<2> principal_values(const PcaMatrix<2>& a);
PcaVector<3> principal_values(const PcaMatrix<3>& a);

/// PCA of the points at(0) … at(n - 1), n > 0: mean and the eigen-decomposition of the
/// covariance.
template <class At>
Pca<AccessedPoint<At>::RowsAtCompileTime> pca(std::size_t n, At&& at, EigenMethod method = EigenMethod::iterative) {
  const auto m = point_moments(n, at);
  Pca<AccessedPoint<At>::RowsAtCompileTime> r;
  static_cast<EigenAxes<AccessedPoint<At>::RowsAtCompileTime>&>(r) = principal_axes(m.covariance(), method);
  r.mean = m.mean;
  return r;
}
template <class S, int D>
Pca<D> pca(const std::vector<Eigen::Matrix<S, D, 1>>& points, EigenMethod method = EigenMethod::iterative) {
  return pca(
      points.size(), [&](std::size_t i) { return points[i].template cast<double>(); }, method);
}

}  // namespace cropsight::geometry
