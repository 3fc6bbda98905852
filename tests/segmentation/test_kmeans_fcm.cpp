#include <gtest/gtest.h>

#include <random>

#include "cropsight/core/error.hpp"
#include "cropsight/segmentation/fuzzy_cmeans.hpp"
#include "cropsight/segmentation/kmeans.hpp"

using namespace cropsight::segmentation;

namespace {
// Three well separated isotropic blobs (5 cm apart, 5 mm spread).
std::vector<Eigen::Vector3f> blobs(std::vector<int>& truth) {
  std::mt19937 rng(11);
  std::normal_distribution<float> g(0, 0.005f);
  const Eigen::Vector3f c[3] = {{0, 0, 0.6f}, {0.05f, 0, 0.6f}, {0, 0.05f, 0.62f}};
  std::vector<Eigen::Vector3f> pts;
  for (int i = 0; i < 900; ++i) {
    pts.push_back(c[i % 3] + Eigen::Vector3f(g(rng), g(rng), g(rng)));
    truth.push_back(i % 3);
  }
  return pts;
}

// Fraction of point pairs on which two labellings agree (same / different cluster): 1 = equal up to renaming.
double rand_index(const std::vector<int>& a, const std::vector<int>& b) {
  long agree = 0, total = 0;
  for (std::size_t i = 0; i < a.size(); i += 3)
    for (std::size_t j = i + 1; j < a.size(); j += 5, ++total) agree += (a[i] == a[j]) == (b[i] == b[j]);
  return double(agree) / double(total);
}
}  // namespace

TEST(KMeans, SeparatesBlobs) {
  std::vector<int> truth;
  const auto pts = blobs(truth);
  KMeansConfig cfg;
  cfg.clusters = 3;
  const auto r = kmeans(pts, cfg);
  EXPECT_GT(rand_index(r.labels, truth), 0.99);
  EXPECT_LT(r.inertia / double(pts.size()), 3 * 0.005 * 0.005 * 1.3);
}

TEST(FuzzyCMeans, SeparatesBlobsAndMembershipsSumToOne) {
  std::vector<int> truth;
  const auto pts = blobs(truth);
  FuzzyCMeansConfig cfg;
  cfg.clusters = 3;
  const auto r = fuzzy_cmeans(pts, cfg);
  EXPECT_GT(rand_index(r.labels, truth), 0.99);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    double s = 0;
    for (int j = 0; j < 3; ++j) s += r.memberships[i * 3 + j];
    EXPECT_NEAR(s, 1.0, 1e-5);
  }
}

TEST(KMeans, RejectsBadInput) {
  std::vector<Eigen::Vector3f> two(2, Eigen::Vector3f::Zero());
  EXPECT_THROW(kmeans(two, KMeansConfig{}), cropsight::Error);
  FuzzyCMeansConfig f;
  f.clusters = 1;
  f.fuzziness = 1.0;
  EXPECT_THROW(fuzzy_cmeans(two, f), cropsight::Error);
}
