// The detector's runtime choice (nn::open_center_detector, center_backend.hpp): auto takes the
// libtorch weights where the plugin loads, and both runtimes give the same boxes and masks of the
// shipped grape model on a shared grape image.
#include <gtest/gtest.h>

#include <cmath>

#include "cropsight/io/image_io.hpp"
#include "cropsight/nn/center_backend.hpp"
#include "cropsight/nn/center_decode.hpp"
#include "cropsight/nn/center_net.hpp"
#include "cropsight/nn/center_onnx.hpp"
#include "testing/testing.hpp"

namespace center_backend_test {
using namespace cropsight;
namespace fs = std::filesystem;

const fs::path kShipped = cropsight::testing::source_dir() / "models" / "detector-grape";

TEST(CenterBackend, AutoTakesLibtorchWhereThePluginLoadsAndAFileKeepsItsOwnRuntime) {
  const auto automatic = nn::open_center_detector(kShipped.string(), nn::DetectorRuntime::automatic, 1);
  EXPECT_EQ(dynamic_cast<nn::CenterNet*>(automatic.get()) != nullptr, nn::libtorch_available());
  const auto opencv = nn::open_center_detector(kShipped.string(), nn::DetectorRuntime::opencv, 1);
  EXPECT_NE(dynamic_cast<nn::CenterNetOnnx*>(opencv.get()), nullptr);
  // A named file is run by its extension; an explicit runtime that contradicts it is an error.
  const auto onnx_file = nn::open_center_detector(kShipped.string() + ".onnx", nn::DetectorRuntime::automatic, 1);
  EXPECT_NE(dynamic_cast<nn::CenterNetOnnx*>(onnx_file.get()), nullptr);
  const std::string e = cropsight::testing::error_message(
      [&] { nn::open_center_detector(kShipped.string() + ".onnx", nn::DetectorRuntime::libtorch, 1); });
  EXPECT_NE(e.find("runtime is libtorch"), std::string::npos) << e;
  EXPECT_NE(cropsight::testing::error_message([&] {
              nn::open_center_detector("no-such-detector", nn::DetectorRuntime::automatic, 1);
            }).find("no such detector model"),
            std::string::npos);
}

// The same weights through both runtimes on a real 1280x720 grape image (flip test on): heads within 1e-4, boxes
// within 0.05 pixel and 1e-4 in score, masks inside the boxes differing in at most 0.01 % of the
// pixels (a score within float rounding of its threshold may land on either side).
TEST(CenterBackend, BothRuntimesGiveTheSameBoxesAndMasksOnAGrapeImage) {
  const fs::path image_file = cropsight::testing::shared_data_dir() / "grape/coco_train/JPEGImages/grape_image_1.jpg";
  CROPSIGHT_REQUIRE_DATA(image_file);
  if (!nn::libtorch_available()) GTEST_SKIP() << "the libtorch plugin is not built";
  const ColorImage image = io::read_color(image_file);
  const nn::CenterNet torch_net = nn::CenterNet::load(kShipped.string() + ".pt", 2);
  nn::CenterNetOnnx onnx_net(kShipped.string() + ".onnx");
  const nn::CenterNetConfig& cfg = onnx_net.config();
  const nn::CenterNetHeads a = torch_net.heads(image), b = onnx_net.heads(image);
  ASSERT_EQ(a.mask.size(), b.mask.size());
  float worst = 0;
  for (std::size_t i = 0; i < a.mask.size(); ++i)
    worst = std::max({worst, std::abs(a.mask[i] - b.mask[i]), std::abs(a.heatmap[i] - b.heatmap[i])});
  EXPECT_LT(worst, 1e-4f);
  // Two threads run the flip test's two images on a thread each (one OpenMP thread apiece): the
  // same heads as one thread running both as one batch.
  const nn::CenterNetHeads one = nn::CenterNet::load(kShipped.string() + ".pt", 1).heads(image);
  float thread_diff = 0;
  for (std::size_t i = 0; i < a.mask.size(); ++i)
    thread_diff = std::max({thread_diff, std::abs(a.mask[i] - one.mask[i]), std::abs(a.size[i] - one.size[i])});
  EXPECT_LT(thread_diff, 1e-5f);
  const auto boxes_a = nn::boxes_from_heads(a, cfg, image.width, image.height);
  const auto boxes_b = nn::boxes_from_heads(b, cfg, image.width, image.height);
  ASSERT_FALSE(boxes_a.empty());
  ASSERT_EQ(boxes_a.size(), boxes_b.size());
  for (std::size_t i = 0; i < boxes_a.size(); ++i) {
    EXPECT_EQ(boxes_a[i].class_id, boxes_b[i].class_id);
    EXPECT_NEAR(boxes_a[i].score, boxes_b[i].score, 1e-4);
    EXPECT_NEAR(boxes_a[i].x1, boxes_b[i].x1, 0.05);
    EXPECT_NEAR(boxes_a[i].y2, boxes_b[i].y2, 0.05);
  }
  const auto masks_a = nn::masks_in_boxes(a, cfg, boxes_a, image.width, image.height);
  const auto masks_b = nn::masks_in_boxes(b, cfg, boxes_a, image.width, image.height);
  for (std::size_t c = 0; c < masks_a.size(); ++c) {
    std::size_t differ = 0;
    for (std::size_t i = 0; i < masks_a[c].data.size(); ++i) differ += masks_a[c].data[i] != masks_b[c].data[i];
    EXPECT_LE(differ, masks_a[c].data.size() / 10000) << "class " << c;
  }
}

}  // namespace center_backend_test
