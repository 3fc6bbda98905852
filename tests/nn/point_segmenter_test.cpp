#include <dlfcn.h>
#include <gtest/gtest.h>

#include <random>

#include "cropsight/core/error.hpp"
#include "cropsight/nn/point_segmenter.hpp"
#include "testing/testing.hpp"

namespace {
using namespace cropsight;
using namespace cropsight::nn;

// A tiny cloud: points on a sphere; label by position band (3 classes), colour loosely tied to
// the label, normals radial.
Cloud tiny_cloud(std::uint32_t seed, int n = 128) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> g;
  Cloud c;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3f p = Eigen::Vector3f(g(rng), g(rng), g(rng)).normalized();
    c.points.push_back(p);
    c.normals.push_back(p);
    const int l = p.x() < -0.3f ? 0 : (p.x() > 0.3f ? 2 : 1);
    c.labels.push_back(l);
    c.colors.emplace_back(0.2f + 0.3f * float(l), 0.5f, 0.5f);
  }
  return c;
}

PointNetConfig tiny_config(const std::string& arch) {
  PointNetConfig c;
  c.arch = arch;
  c.num_classes = 3;
  c.num_points = 128;
  c.sa1_points = 32, c.sa2_points = 16, c.sa3_points = 8;
  c.k1 = 8, c.k2 = 8, c.k3 = 4;
  c.width = 8;
  c.dropout = 0;
  c.augment = false;
  c.lr = 1e-2;
  c.threads = 1;
  return c;
}

void overfits(const std::string& arch) {
  PointSegmenter net(tiny_config(arch));
  const std::vector<Cloud> batch = {tiny_cloud(1), tiny_cloud(2)};
  double first = 0, last = 0, acc = 0;
  for (int it = 0; it < 150; ++it) {
    auto [loss, a] = net.train_step(batch);
    if (it == 0) first = loss;
    last = loss, acc = a;
  }
  EXPECT_LT(last, 0.2 * first) << arch;
  EXPECT_DOUBLE_EQ(acc, 1.0) << arch;
  // The trained net also labels every point of the training clouds correctly in eval mode.
  const auto pred = net.segment(batch[0]);
  int ok = 0;
  for (std::size_t i = 0; i < pred.size(); ++i) ok += pred[i] == batch[0].labels[i];
  EXPECT_GE(ok, int(pred.size()) - 2) << arch;
}

TEST(PointSegmenter, PointResNetOverfitsTwoTinyClouds) { overfits("pointresnet"); }
TEST(PointSegmenter, PointNet2MsgOverfitsTwoTinyClouds) { overfits("pointnet2"); }

TEST(PointSegmenter, SaveLoadGivesIdenticalPredictions) {
  PointSegmenter net(tiny_config("pointresnet"));
  const std::vector<Cloud> batch = {tiny_cloud(3), tiny_cloud(4)};
  for (int it = 0; it < 10; ++it) net.train_step(batch);
  cropsight::testing::TempDir t;
  net.save(t / "m.pt");
  const PointSegmenter back = PointSegmenter::load(t / "m.pt", 1);
  const Cloud big = tiny_cloud(5, 300);  // several passes, padded last chunk
  int passes = 0;
  EXPECT_EQ(back.segment(big, &passes), net.segment(big));
  EXPECT_EQ(passes, 3);
  EXPECT_EQ(back.segment_sampled(big), net.segment_sampled(big));
  EXPECT_EQ(back.segment_sampled(big, true), net.segment_sampled(big, true));
  EXPECT_EQ(net.segment_sampled(big).size(), big.size());
  EXPECT_EQ(back.config().arch, "pointresnet");
  EXPECT_EQ(back.parameter_count(), net.parameter_count());
}

TEST(PointSegmenter, DeterministicGivenSeedAndRejectsBadInput) {
  const std::vector<Cloud> batch = {tiny_cloud(6), tiny_cloud(7)};
  PointSegmenter a(tiny_config("pointresnet")), b(tiny_config("pointresnet"));
  for (int it = 0; it < 3; ++it) EXPECT_DOUBLE_EQ(a.train_step(batch).first, b.train_step(batch).first);
  auto bad = tiny_config("pointresnet");
  bad.features = "rgb";
  EXPECT_THROW(PointSegmenter{bad}, Error);
  Cloud no_colour = tiny_cloud(8);
  no_colour.colors.clear();
  EXPECT_THROW(a.segment(no_colour), Error);
  cropsight::testing::TempDir t;
  EXPECT_THROW(PointSegmenter::load(t / "missing.pt"), Error);
}

// OpenBLAS's spinning thread pool slowed training 2.2x on two cores; a network leaves it at one
// thread (when libtorch's BLAS is OpenBLAS, as on Debian).
TEST(PointSegmenter, OpenBlasRunsSingleThreaded) {
  using GetThreads = int (*)();
  auto get = reinterpret_cast<GetThreads>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  if (!get) GTEST_SKIP() << "libtorch's BLAS is not OpenBLAS here";
  PointSegmenter net(tiny_config("pointresnet"));
  EXPECT_EQ(get(), 1);
}

TEST(PointSegmenter, TrainLoopResumesFromCheckpoint) {
  cropsight::testing::TempDir t;
  auto cfg = tiny_config("pointresnet");
  cfg.epochs = 2;
  cfg.batch_size = 2;
  cfg.val_every = 1;
  cfg.checkpoint = (t / "ckpt.pt").string();
  const std::vector<Cloud> tr = {tiny_cloud(9), tiny_cloud(10)}, va = {tiny_cloud(11)};
  PointSegmenter a(cfg);
  auto logs = a.train(tr, va);
  ASSERT_EQ(logs.size(), 2u);
  EXPECT_GE(logs.back().val_miou, 0.0);
  cfg.epochs = 3;
  PointSegmenter b(cfg);
  logs = b.train(tr, va);  // continues at epoch 3
  ASSERT_EQ(logs.size(), 1u);
  EXPECT_EQ(logs[0].epoch, 3);
}
}  // namespace
