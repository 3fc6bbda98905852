#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>

#include "cropsight/core/error.hpp"
#include "cropsight/nn/center_net.hpp"
#include "nn/center_codec.hpp"
#include "testing/testing.hpp"

namespace {
using namespace cropsight;
using namespace cropsight::nn;

// Heads of the given size with every cell 0 (heatmap, size and offset alike).
CenterNetHeads blank_heads(int classes, int w, int h) {
  CenterNetHeads x;
  x.classes = classes, x.out_w = w, x.out_h = h;
  const std::size_t plane = std::size_t(w) * std::size_t(h);
  x.heatmap.assign(std::size_t(classes) * plane, 0.f);
  x.size.assign(2 * plane, 0.f);
  x.offset.assign(2 * plane, 0.f);
  x.mask.assign(std::size_t(classes) * plane, 0.f);
  return x;
}

void put_object(CenterNetHeads& h, int c, int x, int y, float score, float w, float hh, float dx, float dy) {
  const std::size_t plane = std::size_t(h.out_w) * std::size_t(h.out_h), i = std::size_t(y * h.out_w + x);
  h.heatmap[std::size_t(c) * plane + i] = score;
  h.size[i] = w, h.size[plane + i] = hh;
  h.offset[i] = dx, h.offset[plane + i] = dy;
}

TEST(CenterCodec, DecodesPeaksTopKAndMapsBackThroughTheLetterbox) {
  auto h = blank_heads(2, 16, 16);
  put_object(h, 0, 4, 5, 0.9f, 4, 2, 0.5f, 0.25f);  // centre (4.5, 5.25) cells = (18, 21) px
  put_object(h, 1, 10, 10, 0.6f, 2, 2, 0, 0);
  // A neighbour below its peak is no peak; a weak isolated one is below the threshold.
  h.heatmap[std::size_t(5 * 16 + 5)] = 0.8f;
  h.heatmap[std::size_t(14 * 16 + 1)] = 0.05f;
  const Letterbox same = Letterbox::fit(64, 64, 64, 64, OnnxResize::letterbox);
  auto d = decode_heads(h, same, 0.1f, 100);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d[0].class_id, 0);
  EXPECT_FLOAT_EQ(d[0].score, 0.9f);
  EXPECT_FLOAT_EQ(d[0].x1, 10.f);
  EXPECT_FLOAT_EQ(d[0].x2, 26.f);
  EXPECT_FLOAT_EQ(d[0].y1, 17.f);
  EXPECT_FLOAT_EQ(d[0].y2, 25.f);
  EXPECT_EQ(d[1].class_id, 1);
  EXPECT_FLOAT_EQ(d[1].x1, 36.f);
  EXPECT_FLOAT_EQ(d[1].x2, 44.f);
  // top_k keeps the best.
  d = decode_heads(h, same, 0.1f, 1);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].class_id, 0);
  // A 128 x 64 image letterboxed into 64 x 64: scale 0.5, 16 px of pad above.
  const Letterbox lb = Letterbox::fit(128, 64, 64, 64, OnnxResize::letterbox);
  d = decode_heads(h, lb, 0.1f, 100);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_FLOAT_EQ(d[0].x1, 20.f);
  EXPECT_FLOAT_EQ(d[0].y1, 2.f);
  EXPECT_FLOAT_EQ(d[0].y2, 18.f);
}

TEST(CenterCodec, TargetsPeakAtTheCentreAndDecodeBackToTheBoxes) {
  const std::vector<Detection2D> boxes = {{10, 12, 30, 28, 0, 1}, {40, 40, 60, 56, 1, 1}};
  const CenterTargets t = encode_targets(boxes, {}, 2, 16, 16, 4);
  // Box 0: centre (20, 20) px = (5, 5) cells exactly; 5 x 4 cells.
  EXPECT_EQ(t.index[0], 5 * 16 + 5);
  EXPECT_FLOAT_EQ(t.heatmap[std::size_t(5 * 16 + 5)], 1.f);
  EXPECT_LT(t.heatmap[std::size_t(5 * 16 + 6)], 1.f);
  EXPECT_FLOAT_EQ(t.size[0], 5.f);
  EXPECT_FLOAT_EQ(t.size[1], 4.f);
  EXPECT_FLOAT_EQ(t.offset[0], 0.f);
  EXPECT_FLOAT_EQ(t.reg_mask[0], 1.f);
  EXPECT_FLOAT_EQ(t.reg_mask[2], 0.f);
  EXPECT_TRUE(t.mask.empty());
  EXPECT_GT(gaussian_radius(4, 5), 0.f);
  // Heads that are exactly the targets decode to the boxes.
  auto h = blank_heads(2, 16, 16);
  h.heatmap = t.heatmap;
  for (int k = 0; k < 2; ++k) {
    const auto i = std::size_t(t.index[std::size_t(k)]);
    h.size[i] = t.size[2 * std::size_t(k)], h.size[256 + i] = t.size[2 * std::size_t(k) + 1];
    h.offset[i] = t.offset[2 * std::size_t(k)], h.offset[256 + i] = t.offset[2 * std::size_t(k) + 1];
  }
  const auto d = decode_heads(h, Letterbox::fit(64, 64, 64, 64, OnnxResize::letterbox), 0.5f, 10);
  ASSERT_EQ(d.size(), 2u);
  for (const auto& b : d) EXPECT_GT(iou(b, boxes[std::size_t(b.class_id)]), 0.999f);
}

// Three tiny images: red squares (class 0) and blue bars (class 1) on grey, with masks.
std::vector<DetectionSample> tiny_set() {
  std::vector<DetectionSample> set;
  const int layouts[3][2][4] = {
      {{4, 6, 22, 24}, {36, 30, 60, 42}}, {{30, 8, 50, 28}, {6, 44, 30, 56}}, {{12, 34, 30, 52}, {34, 6, 58, 18}}};
  for (int i = 0; i < 3; ++i) {
    DetectionSample s;
    s.name = "tiny" + std::to_string(i);
    s.image = ColorImage(64, 64, Rgb8{120, 120, 120});
    s.masks = {GrayImage(64, 64), GrayImage(64, 64)};
    for (int c = 0; c < 2; ++c) {
      const auto* b = layouts[i][c];
      for (int y = b[1]; y < b[3]; ++y)
        for (int x = b[0]; x < b[2]; ++x) {
          s.image.at(x, y) = c == 0 ? Rgb8{220, 30, 30} : Rgb8{30, 30, 220};
          s.masks[std::size_t(c)].at(x, y) = 255;
        }
      s.boxes.push_back({float(b[0]), float(b[1]), float(b[2]), float(b[3]), c, 1});
    }
    set.push_back(s);
  }
  return set;
}

CenterNetConfig tiny_config() {
  CenterNetConfig c;
  c.class_names = "square, bar";
  c.input_width = c.input_height = 64;
  c.width = 8;
  c.epochs = 150;
  c.batch_size = 3;
  c.lr = 5e-3;
  c.weight_decay = 0;
  c.threads = 1;
  return c;
}

TEST(CenterNet, OverfitsThreeTinyImages) {
  const auto set = tiny_set();
  CenterNet net(tiny_config());
  EXPECT_EQ(net.class_names(), (std::vector<std::string>{"square", "bar"}));
  std::vector<DetectorEpochLog> logs;
  net.train(set, set, {}, [&](const DetectorEpochLog& l) { logs.push_back(l); });
  ASSERT_EQ(logs.size(), 150u);
  EXPECT_DOUBLE_EQ(logs.back().val_ap50, 1.0);
  EXPECT_LT(logs.back().loss, 0.1 * logs.front().loss);
  EXPECT_GT(logs.front().mask_loss, 0);
  // Every box found (IoU > 0.7, right class) and AP50 1 on the training images.
  for (const auto& s : set) {
    const auto d = net.detect(s.image);
    for (const auto& t : s.boxes) {
      float best = 0;
      for (const auto& b : d)
        if (b.class_id == t.class_id) best = std::max(best, iou(b, t));
      EXPECT_GT(best, 0.7f) << s.name << " class " << t.class_id;
    }
  }
  // The mask head learnt the squares too: the centre cell of square 0 of image 0 is inside.
  const auto h = net.heads(set[0].image);
  EXPECT_GT(h.mask[std::size_t(h.out_w * 3 + 3)], 0.5f);
  EXPECT_LT(h.mask[std::size_t(h.out_w * 14 + 1)], 0.5f);
}

// mask_dice_weight adds a soft Dice term, per class over the batch, to the mask loss: with the
// same weights and batches the first epoch's mask loss rises by the Dice value, which lies in (0, 1]
// (the untrained masks barely overlap their classes' pixels).
TEST(CenterNet, DiceTermAddsToTheMaskLoss) {
  const auto set = tiny_set();
  auto cfg = tiny_config();
  cfg.epochs = 1;
  std::vector<double> mask_loss;
  for (double w : {0.0, 1.0}) {
    cfg.mask_dice_weight = w;
    CenterNet net(cfg);
    net.train(set, {}, {}, [&](const DetectorEpochLog& l) { mask_loss.push_back(l.mask_loss); });
  }
  ASSERT_EQ(mask_loss.size(), 2u);
  EXPECT_GT(mask_loss[1] - mask_loss[0], 0.3);
  EXPECT_LE(mask_loss[1] - mask_loss[0], 1.0);
}

TEST(CenterNet, SaveLoadGivesIdenticalBoxes) {
  const auto set = tiny_set();
  auto cfg = tiny_config();
  cfg.epochs = 60;
  cfg.score_threshold = 0.01;
  CenterNet net(cfg);
  net.train(set, {}, {}, {});
  cropsight::testing::TempDir t;
  net.save(t / "det.pt");
  const CenterNet back = CenterNet::load(t / "det.pt", 1);
  EXPECT_EQ(back.config().class_names, cfg.class_names);
  EXPECT_EQ(back.parameter_count(), net.parameter_count());
  const auto a = net.detect(set[1].image), b = back.detect(set[1].image);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_FALSE(a.empty());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].x1, b[i].x1);
    EXPECT_EQ(a[i].y2, b[i].y2);
    EXPECT_EQ(a[i].score, b[i].score);
    EXPECT_EQ(a[i].class_id, b[i].class_id);
  }
}

TEST(CenterNet, CheckpointResumeEndsWithTheSameWeights) {
  const auto set = tiny_set();
  auto cfg = tiny_config();
  cfg.epochs = 4;
  cropsight::testing::TempDir t;
  CenterNet whole(cfg);
  whole.train(set, {}, {}, {});
  // A run stopped after its second epoch (the epoch callback throws, as a kill would stop it).
  {
    CenterNet first(cfg);
    EXPECT_THROW(first.train(
                     set, {}, {},
                     [](const DetectorEpochLog& l) {
                       if (l.epoch == 2) throw Error("test", "stop");
                     },
                     t / "ck.pt"),
                 Error);
  }
  CenterNet resumed(cfg);
  const auto logs = resumed.train(set, {}, {}, {}, t / "ck.pt");
  ASSERT_EQ(logs.size(), 2u);
  EXPECT_EQ(logs.front().epoch, 3);
  const auto a = whole.heads(set[0].image), b = resumed.heads(set[0].image);
  for (std::size_t i = 0; i < a.heatmap.size(); ++i) ASSERT_NEAR(a.heatmap[i], b.heatmap[i], 1e-5f);
}

TEST(CenterNet, ForeignFilesAreNamed) {
  cropsight::testing::TempDir t;
  cropsight::testing::write_text(t / "bad.pt", "not an archive");
  try {
    CenterNet::load(t / "bad.pt");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.pt"), std::string::npos);
  }
  EXPECT_THROW(CenterNet::load(t / "missing.pt"), Error);
  auto cfg = tiny_config();
  cfg.input_width = 50;
  EXPECT_THROW(CenterNet net(cfg), Error);
  cfg = tiny_config();
  cfg.class_names = " , ";
  EXPECT_THROW(CenterNet net(cfg), Error);
}

}  // namespace

// Flip test: the mirrored blob reverses every row of every channel; the merge averages heatmap,
// sizes and masks with the mirrored heads mirrored back and keeps the offsets.
TEST(CenterCodec, MirroredHeadsAreAveragedBackInPlace) {
  const std::vector<float> blob = {1, 2, 3, 4, 5, 6};  // 3 channels of 2x1
  EXPECT_EQ(mirrored_blob(blob, 2, 1), (std::vector<float>{2, 1, 4, 3, 6, 5}));
  EXPECT_THROW(mirrored_blob(blob, 3, 1), Error);
  CenterNetHeads h, m;
  h.classes = m.classes = 1;
  h.out_w = m.out_w = 3;
  h.out_h = m.out_h = 1;
  h.heatmap = {0.9f, 0.1f, 0.0f};
  m.heatmap = {0.2f, 0.1f, 0.7f};  // the same peak seen from the mirror: cell 2 is cell 0
  h.size = {4, 4, 4, 2, 2, 2};
  m.size = {6, 6, 6, 2, 2, 2};
  h.offset = {0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f};
  m.offset = {0, 0, 0, 0, 0, 0};
  h.mask = {1.0f, 0.0f, 0.0f};
  m.mask = {0.0f, 0.0f, 0.5f};
  merge_mirrored_heads(h, m);
  EXPECT_FLOAT_EQ(h.heatmap[0], 0.8f);
  EXPECT_FLOAT_EQ(h.heatmap[2], 0.1f);
  EXPECT_FLOAT_EQ(h.size[0], 5.0f);
  EXPECT_FLOAT_EQ(h.mask[0], 0.75f);
  EXPECT_FLOAT_EQ(h.mask[2], 0.0f);
  EXPECT_EQ(h.offset, (std::vector<float>{0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f}));
  m.out_w = 2;
  EXPECT_THROW(merge_mirrored_heads(h, m), Error);
}
