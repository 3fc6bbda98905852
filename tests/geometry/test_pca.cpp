#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "cropsight/geometry/pca.hpp"

namespace {
using namespace cropsight::geometry;

// |cos| of the angle between two directions: eigenvector signs are arbitrary.
double alignment(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return std::abs(a.dot(b)) / (a.norm() * b.norm());
}

// The reference covariance, written the textbook way on a data matrix (one point per row).
template <int D, class S>
PcaMatrix<D> reference_covariance(const std::vector<Eigen::Matrix<S, D, 1>>& pts, PcaVector<D>& mean) {
  Eigen::MatrixXd X(pts.size(), D);
  for (std::size_t i = 0; i < pts.size(); ++i) X.row(Eigen::Index(i)) = pts[i].template cast<double>().transpose();
  mean = X.colwise().mean().transpose();
  const Eigen::MatrixXd c = X.rowwise() - mean.transpose();
  return (c.transpose() * c) / double(pts.size());
}

// Six points ±s_k R e_k around t: mean t, covariance R diag(s_k² / 3) R^T exactly.
std::vector<Eigen::Vector3d> rotated_cross(const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
                                           const Eigen::Vector3d& s) {
  std::vector<Eigen::Vector3d> pts;
  for (int k = 0; k < 3; ++k)
    for (double sign : {-1.0, 1.0}) pts.push_back(t + sign * s[k] * R.col(k));
  return pts;
}

TEST(Pca, KnownCovarianceFarFromTheOrigin) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, -0.5).normalized()).toRotationMatrix();
  // 1000 km from the origin: a one-pass sum of p p^T leaves 1e-3 of error here (measured); the
  // centred second pass keeps it near 1e-10.
  const Eigen::Vector3d t(1e6, -2e6, 3e6), s(1, 2, 3);
  const auto pts = rotated_cross(R, t, s);
  const Eigen::Vector3d var = s.cwiseProduct(s) / 3.0;  // 1/3, 4/3, 3 (ascending)
  const Eigen::Matrix3d cov = R * var.asDiagonal() * R.transpose();

  const auto m = point_moments(pts);
  EXPECT_EQ(m.count, 6u);
  EXPECT_LT((m.mean - t).norm(), 1e-9);
  EXPECT_LT((m.covariance() - cov).cwiseAbs().maxCoeff(), 1e-8);
  EXPECT_LT((m.scatter - 6.0 * cov).cwiseAbs().maxCoeff(), 1e-8);

  for (EigenMethod method : {EigenMethod::iterative, EigenMethod::closed_form}) {
    const auto p = pca(pts, method);
    EXPECT_LT((p.mean - t).norm(), 1e-9);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(p.eigenvalues[k], var[k], 1e-8) << k;
      EXPECT_GT(alignment(p.axes.col(k), R.col(k)), 1 - 1e-9) << k;
      EXPECT_NEAR(p.axes.col(k).norm(), 1.0, 1e-12);
    }
    EXPECT_EQ(p.normal(), p.axes.col(0));
    EXPECT_EQ(p.major(), p.axes.col(2));
  }
}

TEST(Pca, MatchesEigenOnRandomPoints) {
  std::mt19937 rng(7);
  std::normal_distribution<float> g(0.f, 1.f);
  const Eigen::Matrix3f R = Eigen::AngleAxisf(1.1f, Eigen::Vector3f(-0.3f, 1.f, 0.4f).normalized()).toRotationMatrix();
  std::vector<Eigen::Vector3f> pts;
  for (int i = 0; i < 500; ++i)
    pts.push_back(R * Eigen::Vector3f(0.01f * g(rng), 0.05f * g(rng), 0.2f * g(rng)) +
                  Eigen::Vector3f(0.3f, -0.2f, 1.5f));

  PcaVector<3> mean;
  const PcaMatrix<3> cov = reference_covariance(pts, mean);
  const auto m = point_moments(pts);
  EXPECT_LT((m.mean - mean).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((m.covariance() - cov).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((point_mean(pts) - mean).cwiseAbs().maxCoeff(), 1e-12);

  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
  for (EigenMethod method : {EigenMethod::iterative, EigenMethod::closed_form}) {
    const auto p = pca(pts, method);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(p.eigenvalues[k], es.eigenvalues()[k], 1e-9 * es.eigenvalues()[2]) << k;
      EXPECT_GT(alignment(p.axes.col(k), es.eigenvectors().col(k)), 1 - 1e-6) << k;
    }
    EXPECT_LE(p.eigenvalues[0], p.eigenvalues[1]);
    EXPECT_LE(p.eigenvalues[1], p.eigenvalues[2]);
    // The generating axes: smallest spread along R e_x, largest along R e_z.
    EXPECT_GT(alignment(p.normal(), R.col(0).cast<double>()), 0.99);
    EXPECT_GT(alignment(p.major(), R.col(2).cast<double>()), 0.999);
  }
  const PcaVector<3> values = principal_values(cov);
  EXPECT_LT((values - es.eigenvalues()).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(Pca, TwoDimensionalAxes) {
  std::mt19937 rng(3);
  std::normal_distribution<double> g(0.0, 1.0);
  const Eigen::Vector2d along = Eigen::Vector2d(3, 4).normalized(), across(-along.y(), along.x());
  std::vector<Eigen::Vector2d> pts;
  for (int i = 0; i < 400; ++i) pts.push_back(Eigen::Vector2d(5, -7) + 0.3 * g(rng) * along + 0.05 * g(rng) * across);

  PcaVector<2> mean;
  const PcaMatrix<2> cov = reference_covariance(pts, mean);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(cov);
  for (EigenMethod method : {EigenMethod::iterative, EigenMethod::closed_form}) {
    const auto p = pca(pts, method);
    EXPECT_LT((p.mean - mean).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_NEAR(p.eigenvalues[0], es.eigenvalues()[0], 1e-12);
    EXPECT_NEAR(p.eigenvalues[1], es.eigenvalues()[1], 1e-12);
    EXPECT_GT(alignment(p.major(), along), 0.999);
    EXPECT_GT(alignment(p.normal(), across), 0.999);
  }
  EXPECT_LT((principal_values(cov) - es.eigenvalues()).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(Pca, PlaneNormalIsTheSmallestAxis) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < 300; ++i) {
    const double x = u(rng), y = u(rng);
    pts.emplace_back(x, y, 1.0 + 0.2 * x - 0.1 * y);  // z = 1 + 0.2 x - 0.1 y
  }
  const Eigen::Vector3d n = Eigen::Vector3d(-0.2, 0.1, 1.0).normalized();
  const auto p = pca(pts);
  EXPECT_GT(alignment(p.normal(), n), 1 - 1e-12);
  EXPECT_NEAR(p.eigenvalues[0], 0.0, 1e-14);
  EXPECT_NEAR(std::abs(p.normal().dot(p.mean)), n.z(), 1e-12);  // the mean lies on the plane n . x = n_z
}

TEST(Pca, AnAccessorSeesTheSameNumbersAsAList) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  std::vector<Eigen::Vector3f> all;
  for (int i = 0; i < 100; ++i) all.emplace_back(u(rng), u(rng), u(rng));
  const std::vector<int> idx = {7, 3, 99, 42, 0, 18, 55};
  std::vector<Eigen::Vector3f> subset;
  for (int i : idx) subset.push_back(all[std::size_t(i)]);
  const auto a = point_moments(idx.size(), [&](std::size_t q) { return all[std::size_t(idx[q])].cast<double>(); });
  const auto b = point_moments(subset);
  EXPECT_EQ(a.mean, b.mean);  // same order of additions: bit-identical
  EXPECT_EQ(a.scatter, b.scatter);
}

TEST(Pca, NoPointsGiveZeroMoments) {
  const auto m = point_moments(std::vector<Eigen::Vector3f>{});
  EXPECT_EQ(m.count, 0u);
  EXPECT_EQ(m.mean, Eigen::Vector3d::Zero());
  EXPECT_EQ(m.scatter, Eigen::Matrix3d::Zero());
  EXPECT_EQ(point_mean(std::vector<Eigen::Vector2d>{}), Eigen::Vector2d::Zero());
}

}  // namespace
