// The eigen-solvers of geometry/pca.hpp, compiled once for 2-D and 3-D. Each is exactly the
// Eigen call its callers made before (compute / computeDirect / EigenvaluesOnly), so their
// results are unchanged to the bit.
#include "cropsight/geometry/pca.hpp"

#include <Eigen/Eigenvalues>

namespace cropsight::geometry {
namespace {

template <int D>
EigenAxes<D> decompose(const PcaMatrix<D>& a, EigenMethod method) {
  Eigen::SelfAdjointEigenSolver<PcaMatrix<D>> es;
  if (method == EigenMethod::closed_form)
    es.computeDirect(a);
  else
    es.compute(a);
  EigenAxes<D> r;
  r.eigenvalues = es.eigenvalues();
  r.axes = es.eigenvectors();
  return r;
}

template <int D>
PcaVector<D> values(const PcaMatrix<D>& a) {
  return Eigen::SelfAdjointEigenSolver<PcaMatrix<D>>(a, Eigen::EigenvaluesOnly).eigenvalues();
}

}  // namespace

EigenAxes<2> principal_axes(const PcaMatrix<2>& a, EigenMethod method) { return decompose<2>(a, method); }
EigenAxes<3> principal_axes(const PcaMatrix<3>& a, EigenMethod method) { return decompose<3>(a, method); }
PcaVector<2> principal_values(const PcaMatrix<2>& a) { return values<2>(a); }
PcaVector<3> principal_values(const PcaMatrix<3>& a) { return values<3>(a); }

}  // namespace cropsight::geometry
