#include <dlfcn.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>

#include "cropsight/core/error.hpp"
#include "cropsight/core/threads.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/nn/point_segmenter.hpp"
#include "testing/testing.hpp"

namespace {
using namespace cropsight;
using namespace cropsight::nn;

std::string io_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

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

void overfits(const std::string& arch, double lovasz_weight = 0.0) {
  auto cfg = tiny_config(arch);
  cfg.lovasz_weight = lovasz_weight;
  PointSegmenter net(cfg);
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
TEST(PointSegmenter, PointResNetWithLovaszOverfitsTwoTinyClouds) { overfits("pointresnet", 1.0); }

// lovasz_weight adds the Lovász-softmax term (an IoU surrogate in [0, 1] per class, averaged) to
// the cross-entropy: on the same initial weights the first step's loss rises by w × a value in
// (0, 1] (the untrained net is far from every class's IoU of 1), and by nothing at weight 0.
TEST(PointSegmenter, LovaszTermAddsABoundedIouSurrogate) {
  const std::vector<Cloud> batch = {tiny_cloud(1), tiny_cloud(2)};
  auto first_loss = [&](double w) {
    auto cfg = tiny_config("pointresnet");
    cfg.lovasz_weight = w;
    PointSegmenter net(cfg);  // same seed: same initial weights
    return net.train_step(batch).first;
  };
  const double ce = first_loss(0.0), one = first_loss(1.0), two = first_loss(2.0);
  EXPECT_GT(one - ce, 0.05);
  EXPECT_LE(one - ce, 1.0 + 1e-6);
  EXPECT_NEAR(two - ce, 2.0 * (one - ce), 1e-4);
}

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

// fuzz_network_archive's finding (fuzz/regressions/network_archive/): libtorch does not check
// its archives' CRC-32s, and its TorchScript parser crashed (SIGSEGV) on a damaged one. Every
// entry is checked first (io/zip_check.hpp): a flipped byte anywhere, in the deflated code or
// in the stored weights, and a truncated file are one clear Error.
TEST(PointSegmenter, DamagedArchivesAreErrorsNotCrashes) {
  cropsight::testing::TempDir t;
  PointSegmenter(tiny_config("pointresnet")).save(t / "m.pt");
  const std::string good = cropsight::io::read_file(t / "m.pt");
  // The first byte of an entry's data: after its local header (30 bytes), name and extra field.
  const auto data_of = [&](const std::string& name_part) {
    const std::size_t name = good.find(name_part), header = good.rfind(std::string("PK\3\4", 4), name);
    const auto u16 = [&](std::size_t at) {
      return std::size_t(std::uint8_t(good[at])) | std::size_t(std::uint8_t(good[at + 1])) << 8;
    };
    return header + 30 + u16(header + 26) + u16(header + 28);
  };
  const auto flipped = [&](std::size_t at, char mask) {
    std::string b = good;
    b[at] = char(b[at] ^ mask);
    return b;
  };
  const std::vector<std::pair<std::string, std::string>> damaged = {
      {"flipped_code", flipped(data_of("code/") + 3, 0x20)},      // deflated TorchScript
      {"flipped_weights", flipped(data_of("data/0") + 5, 0x01)},  // stored tensor bytes
      {"truncated", good.substr(0, good.size() / 2)},
  };
  for (const auto& [name, bytes] : damaged) {
    cropsight::io::write_file_atomic(t / (name + ".pt"), bytes);
    try {
      (void)PointSegmenter::load(t / (name + ".pt"), 1);
      ADD_FAILURE() << name << " loaded";
    } catch (const cropsight::Error& e) {
      EXPECT_EQ(e.where(), (t / (name + ".pt")).string());
      EXPECT_NE(std::string(e.what()).find("damaged model archive"), std::string::npos) << name << ": " << e.what();
    }
  }
}

// Test-time augmentation: votes = 1 is the plain cover; votes = N covers the cloud N times
// (N times the passes), rotated about the vertical axis, and gives a label to every point.
// A network trained with rotation augmentation keeps its accuracy under the rotated covers.
TEST(PointSegmenter, VotesCoverTheCloudRotated) {
  auto cfg = tiny_config("pointresnet");
  cfg.augment = true;  // rotations about y, as the votes use
  cfg.scale_min = cfg.scale_max = 1.0;
  cfg.jitter_sigma = 0.0;
  cfg.colour_jitter = 0.0;
  PointSegmenter net(cfg);
  // Labels by height (y bands), which rotations about y keep.
  auto by_height = [](std::uint32_t seed, int n) {
    Cloud c = tiny_cloud(seed, n);
    for (std::size_t i = 0; i < c.size(); ++i) {
      const float y = c.points[i].y();
      c.labels[i] = y < -0.3f ? 0 : (y > 0.3f ? 2 : 1);
      c.colors[i] = Eigen::Vector3f(0.5f, 0.5f, 0.5f);
    }
    return c;
  };
  const std::vector<Cloud> batch = {by_height(11, 128), by_height(12, 128)};
  for (int it = 0; it < 200; ++it) net.train_step(batch);
  const Cloud big = by_height(13, 300);
  int passes = 0;
  EXPECT_EQ(net.segment(big, nullptr, 1), net.segment(big));
  const auto voted = net.segment(big, &passes, 4);
  EXPECT_EQ(passes, 12);  // 3 chunks of 128 per cover
  ASSERT_EQ(voted.size(), big.size());
  auto accuracy = [&](const std::vector<int>& pred) {
    int ok = 0;
    for (std::size_t i = 0; i < pred.size(); ++i) ok += pred[i] == big.labels[i];
    return double(ok) / double(pred.size());
  };
  const double plain = accuracy(net.segment(big)), rotated = accuracy(voted);
  EXPECT_GE(plain, 0.8);
  EXPECT_GE(rotated, plain - 0.03) << "rotation-trained net under rotated votes";
  EXPECT_EQ(net.segment(big, nullptr, 4), voted);  // deterministic
  EXPECT_THROW(net.segment(big, nullptr, 0), Error);
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

// The rotated passes of the sampled mode run on worker threads (one pass each, libtorch's
// operators single-threaded there): the same labels and probabilities as one pass at a time.
TEST(PointSegmenter, PassesOnThreadsEqualOneAtATime) {
  auto cfg = tiny_config("pointresnet");
  cfg.threads = 2;
  PointSegmenter net(cfg);
  const std::vector<Cloud> batch = {tiny_cloud(21), tiny_cloud(22)};
  for (int it = 0; it < 5; ++it) net.train_step(batch);
  const Cloud big = tiny_cloud(23, 300);
  std::vector<std::vector<int>> idx;
  std::vector<float> angles;
  for (int v = 0; v < 5; ++v) {
    idx.push_back(net.sample_for_pass(big, false, v));
    angles.push_back(1.1f * float(v));
  }
  for (int threads : {1, 2, 3}) {
    std::vector<std::vector<float>> proba;
    const auto labels = net.predict_passes(big, idx, angles, threads, &proba);
    ASSERT_EQ(labels.size(), idx.size());
    ASSERT_EQ(proba.size(), idx.size());
    for (std::size_t v = 0; v < idx.size(); ++v) {
      std::vector<float> one;
      EXPECT_EQ(labels[v], net.predict_at(big, idx[v], angles[v], &one)) << threads << " threads, pass " << v;
      EXPECT_EQ(proba[v], one) << threads << " threads, pass " << v;  // the same floats
    }
    EXPECT_EQ(net.predict_passes(big, idx, angles, threads), labels);
  }
  EXPECT_THROW(net.predict_passes(big, idx, {0.f}, 2), Error);
  auto bad = idx;
  bad[3][0] = int(big.size());
  EXPECT_THROW(net.predict_passes(big, bad, angles, 2), Error);
  EXPECT_TRUE(net.predict_passes(big, {}, {}, 2).empty());
}

// OpenBLAS's spinning thread pool slowed training 2.2x on two cores; a network leaves it at one
// thread (when libtorch's BLAS is OpenBLAS, as on Debian).
TEST(PointSegmenter, OpenBlasRunsSingleThreaded) {
  // The backend plugin (and with it libtorch and its BLAS) is loaded by the first network.
  PointSegmenter net(tiny_config("pointresnet"));
  using GetThreads = int (*)();
  auto get = reinterpret_cast<GetThreads>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  if (!get) GTEST_SKIP() << "libtorch's BLAS is not OpenBLAS here";
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
// Every training and architecture field is checked, named, before libtorch sees it: these values
// crashed (batch_size 0), hung (threads 100000), trained nothing (batch_size 1) or gave stack traces.
TEST(PointSegmenter, ConfigFieldsAreValidated) {
  auto expect_named = [](void (*set)(PointNetConfig&), const std::string& key) {
    auto c = tiny_config("pointresnet");
    set(c);
    try {
      c.validate("cfg");
      ADD_FAILURE() << key << " accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.where(), "cfg");
      EXPECT_EQ(e.problem().rfind("'" + key + "'", 0), 0u) << e.what();
    }
    EXPECT_THROW(PointSegmenter{c}, Error) << key;
  };
  expect_named([](PointNetConfig& c) { c.batch_size = 0; }, "batch_size");
  expect_named([](PointNetConfig& c) { c.batch_size = 1; }, "batch_size");
  expect_named([](PointNetConfig& c) { c.lr = -1; }, "lr");
  expect_named([](PointNetConfig& c) { c.lr = std::numeric_limits<double>::infinity(); }, "lr");
  expect_named([](PointNetConfig& c) { c.dropout = 1; }, "dropout");
  expect_named([](PointNetConfig& c) { c.width = 0; }, "width");
  expect_named([](PointNetConfig& c) { c.k1 = 0; }, "k1");
  expect_named([](PointNetConfig& c) { c.epochs = 0; }, "epochs");
  expect_named([](PointNetConfig& c) { c.threads = 0; }, "threads");
  expect_named([](PointNetConfig& c) { c.lovasz_weight = -1; }, "lovasz_weight");
  expect_named([](PointNetConfig& c) { c.lovasz_weight = std::nan(""); }, "lovasz_weight");
  expect_named([](PointNetConfig& c) { c.threads = cropsight::kMaxThreads + 1; }, "threads");
  expect_named([](PointNetConfig& c) { c.arch = "resnet"; }, "arch");
  expect_named([](PointNetConfig& c) { c.scale_max = 0.5; }, "scale_max");
  EXPECT_NO_THROW(tiny_config("pointnet2").validate("cfg"));
  EXPECT_NO_THROW(PointNetConfig{}.validate("cfg"));
}

// A checkpoint or model of another shape is refused with the file's name (libtorch's load would
// swap in the wrong-sized tensors and crash later); saving to a folder leaves no temporary.
TEST(PointSegmenter, BadFilesAreNamed) {
  cropsight::testing::TempDir t;
  auto cfg = tiny_config("pointresnet");
  cfg.epochs = 1;
  cfg.batch_size = 2;
  cfg.checkpoint = (t / "ck.pt").string();
  const std::vector<Cloud> tr = {tiny_cloud(12), tiny_cloud(13)};
  PointSegmenter a(cfg);
  a.train(tr, {});
  a.save(t / "m.pt");
  cfg.width = 16;
  cfg.epochs = 2;
  PointSegmenter wide(cfg);
  try {
    wide.train(tr, {});
    ADD_FAILURE() << "a checkpoint of width 8 resumed a net of width 16";
  } catch (const Error& e) {
    EXPECT_EQ(e.where(), cfg.checkpoint);
    EXPECT_NE(e.problem().find("do not fit"), std::string::npos) << e.what();
  }
  std::ofstream(t / "half.pt", std::ios::binary) << io_bytes(t / "m.pt").substr(0, 100);
  try {
    PointSegmenter::load(t / "half.pt");
    ADD_FAILURE() << "a truncated model loaded";
  } catch (const Error& e) {
    EXPECT_EQ(e.where(), (t / "half.pt").string());
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
  }
  EXPECT_THROW(PointSegmenter::load(t / "m.pt", 0), Error);
  std::filesystem::create_directories(t / "dir.pt");
  EXPECT_THROW(a.save(t / "dir.pt"), Error);
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(t.path())) files += e.path().filename() != "dir.pt";
  EXPECT_EQ(files, 3);  // ck.pt, m.pt, half.pt: no temporary
}
}  // namespace
