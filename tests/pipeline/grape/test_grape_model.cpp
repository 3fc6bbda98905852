// pipeline::grape::Model's sampled (paper) mode for networks: with carry_k = 1 it must give exactly the
// network's own segment_sampled (nearest-neighbour carry-back), and its options are checked.
#include <gtest/gtest.h>

#include <random>

#include "cropsight/core/error.hpp"
#include "cropsight/nn/point_segmenter.hpp"
#include "cropsight/pipeline/grape/model.hpp"
#include "testing/testing.hpp"

namespace {
using namespace cropsight;

Cloud sphere_cloud(std::uint32_t seed, int n) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> g;
  Cloud c;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3f p = Eigen::Vector3f(g(rng), g(rng), g(rng)).normalized();
    const int l = p.x() < 0 ? 1 : 3;
    c.points.push_back(p);
    c.normals.push_back(p);
    c.colors.emplace_back(l == 1 ? 0.2f : 0.7f, 0.5f, 0.4f);
    c.labels.push_back(l);
  }
  return c;
}

nn::PointNetConfig tiny_net_config() {
  nn::PointNetConfig cfg;
  cfg.num_points = 64;
  cfg.sa1_points = 16, cfg.sa2_points = 8, cfg.sa3_points = 4;
  cfg.k1 = cfg.k2 = 8, cfg.k3 = 4;
  cfg.width = 4;
  cfg.threads = 1;
  return cfg;
}

TEST(GrapeModel, SampledModeMatchesTheNetworksNearestNeighbourCarryBack) {
  const nn::PointNetConfig cfg = tiny_net_config();
  nn::PointSegmenter net(cfg);
  const std::vector<Cloud> batch = {sphere_cloud(1, 64), sphere_cloud(2, 64)};
  for (int i = 0; i < 5; ++i) net.train_step(batch);
  cropsight::testing::TempDir t;
  net.save(t / "n.pt");

  auto model = pipeline::grape::Model::load(t / "n.pt", 1);
  const Cloud big = sphere_cloud(3, 500);
  model.set_sampled(true, false, 1);
  EXPECT_EQ(model.segment(big), net.segment_sampled(big));
  model.set_sampled(true, true, 1);
  EXPECT_EQ(model.segment(big), net.segment_sampled(big, true));
  model.set_sampled(true, false, 4);  // colour-guided vote: every point labelled, in range
  const auto voted = model.segment(big);
  ASSERT_EQ(voted.size(), big.size());
  for (int l : voted) EXPECT_TRUE(l >= 0 && l < cfg.num_classes);
  // The sample keeps the network's own labels under any carry-back.
  const auto idx = net.sample_for_pass(big);
  const auto at = net.predict_at(big, idx);
  for (std::size_t s = 0; s < idx.size(); ++s) EXPECT_EQ(voted[std::size_t(idx[s])], at[s]);

  EXPECT_THROW(model.set_sampled(true, false, 0), Error);
  // --votes in the sampled mode: one vote is the plain pass; three give every point a label in
  // range, and points the passes agree on keep that label.
  model.set_sampled(true, false, 1);
  model.set_votes(1);
  EXPECT_EQ(model.segment(big), net.segment_sampled(big));
  model.set_votes(3);
  const auto v3 = model.segment(big);
  ASSERT_EQ(v3.size(), big.size());
  for (int l : v3) EXPECT_TRUE(l >= 0 && l < cfg.num_classes);
  // --votes in the every-point mode: the network's rotated covers.
  model.set_sampled(false);
  model.set_votes(2);
  EXPECT_EQ(model.segment(big), net.segment(big, nullptr, 2));
  EXPECT_THROW(model.set_votes(0), Error);
  model.set_votes(1);
  EXPECT_THROW(net.predict_at(big, {0, 1, 2}), Error);
  EXPECT_TRUE(model.segment(Cloud{}).empty());
}
// Ensemble: the argmax of (1 - w) · own scores + w · partner's. w = 0 is the model alone, w = 1
// the partner alone; scores() rows are probabilities.
TEST(GrapeModel, EnsembleMixesTheTwoModelsScores) {
  const nn::PointNetConfig cfg = tiny_net_config();
  nn::PointSegmenter a(cfg), b(cfg);
  const std::vector<Cloud> batch = {sphere_cloud(1, 64), sphere_cloud(2, 64)};
  for (int i = 0; i < 5; ++i) a.train_step(batch);
  for (int i = 0; i < 2; ++i) b.train_step(batch);
  cropsight::testing::TempDir t;
  a.save(t / "a.pt");
  b.save(t / "b.pt");
  auto ma = pipeline::grape::Model::load(t / "a.pt", 1);
  const auto mb = std::make_shared<const pipeline::grape::Model>(pipeline::grape::Model::load(t / "b.pt", 1));
  const Cloud big = sphere_cloud(3, 300);
  const auto alone = ma.segment(big), partner = mb->segment(big);
  const auto sa = ma.scores(big), sb = mb->scores(big);
  ASSERT_EQ(sa.size(), big.size() * 6);
  for (std::size_t i = 0; i < big.size(); ++i) {
    float sum = 0.f;
    for (int c = 0; c < 6; ++c) sum += sa[i * 6 + std::size_t(c)];
    EXPECT_NEAR(sum, 1.f, 1e-4f);
  }
  ma.set_ensemble(mb, 0.0);
  EXPECT_EQ(ma.segment(big), alone);
  ma.set_ensemble(mb, 1.0);
  EXPECT_EQ(ma.segment(big), partner);
  ma.set_ensemble(mb, 0.5);
  const auto mixed = ma.segment(big);
  for (std::size_t i = 0; i < big.size(); ++i) {
    int best = 0;
    for (int c = 1; c < 6; ++c)
      if (sa[i * 6 + std::size_t(c)] + sb[i * 6 + std::size_t(c)] >
          sa[i * 6 + std::size_t(best)] + sb[i * 6 + std::size_t(best)])
        best = c;
    EXPECT_EQ(mixed[i], best) << i;
  }
  EXPECT_THROW(ma.set_ensemble(mb, 1.5), Error);
  ma.set_ensemble(nullptr);
  EXPECT_EQ(ma.segment(big), alone);
}
}  // namespace
