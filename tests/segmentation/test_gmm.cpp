#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <random>

#include "cropsight/core/error.hpp"
#include "cropsight/segmentation/gmm.hpp"
#include "segmentation/gmm_kernels.hpp"

using namespace cropsight::segmentation;

namespace {

struct Truth {
  std::vector<Eigen::Vector3d> means;
  std::vector<Eigen::Matrix3d> covs;
  std::vector<double> weights;
};

// Draws n points from a known mixture; `labels` receives the generating component.
std::vector<Eigen::Vector3f> sample(const Truth& t, int n, std::uint32_t seed, std::vector<int>* labels = nullptr) {
  std::mt19937 rng(seed);
  std::discrete_distribution<int> pick(t.weights.begin(), t.weights.end());
  std::normal_distribution<double> g(0, 1);
  std::vector<Eigen::Vector3f> pts;
  for (int i = 0; i < n; ++i) {
    const int j = pick(rng);
    const Eigen::Matrix3d l = t.covs[j].llt().matrixL();
    const Eigen::Vector3d z(g(rng), g(rng), g(rng));
    pts.push_back((t.means[j] + l * z).cast<float>());
    if (labels) labels->push_back(j);
  }
  return pts;
}

Truth three_blobs() {
  Truth t;
  t.means = {{0.0, 0.0, 0.6}, {0.15, 0.02, 0.65}, {-0.05, 0.12, 0.7}};
  Eigen::Matrix3d a;
  a << 4e-4, 1e-4, 0, 1e-4, 2e-4, 0, 0, 0, 1e-4;
  Eigen::Matrix3d b = Eigen::Vector3d(1e-4, 9e-4, 4e-5).asDiagonal();
  Eigen::Matrix3d c;
  c << 3e-4, -1e-4, 5e-5, -1e-4, 3e-4, 0, 5e-5, 0, 2e-4;
  t.covs = {a, b, c};
  t.weights = {0.5, 0.3, 0.2};
  return t;
}

}  // namespace

TEST(Gmm, RecoversKnownMixture) {
  const Truth t = three_blobs();
  std::vector<int> truth_labels;
  const auto pts = sample(t, 6000, 42, &truth_labels);
  GmmConfig cfg;
  cfg.components = 3;
  const GmmResult r = fit_gmm(pts, cfg);
  ASSERT_EQ(r.model.size(), 3);
  for (int j = 0; j < 3; ++j) {
    // Match each true component to the nearest estimated mean.
    int best = 0;
    for (int e = 1; e < 3; ++e)
      if ((r.model.means[e] - t.means[j]).norm() < (r.model.means[best] - t.means[j]).norm()) best = e;
    EXPECT_LT((r.model.means[best] - t.means[j]).norm(), 3e-3) << "component " << j;
    EXPECT_NEAR(r.model.weights[best], t.weights[j], 0.03);
    EXPECT_LT((r.model.covariances[best] - t.covs[j]).norm(), 0.15 * t.covs[j].norm());
  }
  // The reported log-likelihood is the model's (checked in double precision).
  EXPECT_NEAR(r.log_likelihood, gmm_mean_log_likelihood(r.model, pts), 1e-3);
  EXPECT_TRUE(r.converged);
}

TEST(Gmm, AgreesWithOpenCvEmFromTheSameStart) {
  const Truth t = three_blobs();
  const auto pts = sample(t, 2048, 7);
  GmmConfig cfg;
  cfg.components = 10;  // more components than blobs: the pipeline's setting
  cfg.tolerance = 1e-5;
  cfg.max_iterations = 40;  // cv::ml::EM needs ~60 ms per iteration here; keep the test short
  const GmmModel init = gmm_initial_model(pts, cfg);
  const GmmResult ours = fit_gmm(pts, cfg);
  const GmmResult ref = fit_gmm_opencv(pts, cfg, &init);
  // Same start, same algorithm: same local optimum (log-likelihoods per point within 0.01 nats).
  EXPECT_NEAR(ours.log_likelihood, ref.log_likelihood, 0.01);
  EXPECT_NEAR(gmm_mean_log_likelihood(ours.model, pts), ref.log_likelihood, 0.01);
  // And OpenCV's own initialisation does not find a clearly better optimum.
  const GmmResult ref_own = fit_gmm_opencv(pts, cfg, nullptr);
  EXPECT_GT(ours.log_likelihood, ref_own.log_likelihood - 0.05);
}

TEST(Gmm, LabelsAreArgmaxAndCoverPoints) {
  const auto pts = sample(three_blobs(), 1000, 3);
  GmmConfig cfg;
  cfg.components = 3;
  const GmmResult r = fit_gmm(pts, cfg);
  ASSERT_EQ(r.labels.size(), pts.size());
  for (int l : r.labels) EXPECT_TRUE(l >= 0 && l < 3);
  double ws = 0;
  for (double w : r.model.weights) ws += w;
  EXPECT_NEAR(ws, 1.0, 1e-9);
}

TEST(Gmm, DeterministicPerSeed) {
  const auto pts = sample(three_blobs(), 2000, 5);
  GmmConfig cfg;
  const GmmResult a = fit_gmm(pts, cfg), b = fit_gmm(pts, cfg);
  EXPECT_EQ(a.labels, b.labels);
  EXPECT_DOUBLE_EQ(a.log_likelihood, b.log_likelihood);
}

TEST(Gmm, Avx2VariantMatchesThePortableOne) {
  // fit_gmm() runs the AVX2 + FMA build of the EM where the CPU has it; it must give the fit of
  // the portable SSE2 build (fused multiply-adds round differently, so not bit for bit): K = 10
  // on a 7-blob mixture, as in the seedling pipeline.
  if (!em_avx2::available()) GTEST_SKIP() << "this CPU (or build) has no AVX2 + FMA variant";
  Truth t = three_blobs();
  for (int j = 0; j < 4; ++j) {
    t.means.push_back(Eigen::Vector3d(0.1 * j - 0.2, -0.1, 0.62 + 0.02 * j));
    t.covs.push_back(Eigen::Vector3d(2e-4, 1e-4 * (j + 1), 5e-5).asDiagonal());
    t.weights.push_back(0.1);
  }
  const auto pts = sample(t, 4096, 11);
  GmmConfig cfg;
  const GmmResult a = em_portable::fit(pts, cfg), b = em_avx2::fit(pts, cfg);
  EXPECT_NEAR(a.log_likelihood, b.log_likelihood, 1e-3 * std::fabs(a.log_likelihood));
  int same = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) same += a.labels[i] == b.labels[i];
  EXPECT_GE(same, int(0.99 * pts.size())) << "iterations " << a.iterations << " vs " << b.iterations;
  for (int j = 0; j < cfg.components; ++j) EXPECT_LT((a.model.means[j] - b.model.means[j]).norm(), 1e-3) << j;
}

TEST(Gmm, RejectsBadInput) {
  GmmConfig cfg;
  std::vector<Eigen::Vector3f> few(5, Eigen::Vector3f::Zero());
  EXPECT_THROW(fit_gmm(few, cfg), cropsight::Error);
  auto pts = sample(three_blobs(), 100, 1);
  pts[3].x() = std::nanf("");
  EXPECT_THROW(fit_gmm(pts, cfg), cropsight::Error);
  cfg.components = 0;
  EXPECT_THROW(fit_gmm(sample(three_blobs(), 100, 1), cfg), cropsight::Error);
}
