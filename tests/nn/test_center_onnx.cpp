// The detector's ONNX export: OpenCV DNN on the exported file gives the boxes libtorch gives
// (within 1e-3), and files that are not the project's detector are one Error naming the file.
#include <gtest/gtest.h>

#include <fstream>

#include "cropsight/core/error.hpp"
#include "cropsight/nn/center_decode.hpp"
#include "cropsight/nn/center_net.hpp"
#include "cropsight/nn/center_onnx.hpp"
#include "testing/testing.hpp"

#ifdef CROPSIGHT_HAVE_ONNX
#include <onnx/onnx_pb.h>
#endif

namespace {
using namespace cropsight;
using namespace cropsight::nn;

std::string onnx_error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

ColorImage scene(int w, int h) {
  ColorImage im(w, h, Rgb8{110, 120, 100});
  for (int y = h / 4; y < h / 2; ++y)
    for (int x = w / 5; x < w / 2; ++x) im.at(x, y) = Rgb8{200, 60, 40};
  for (int y = h / 2; y < h - 6; ++y)
    for (int x = w / 2 + 4; x < w - 8; ++x) im.at(x, y) = Rgb8{40, 60, 200};
  return im;
}

#ifdef CROPSIGHT_HAVE_ONNX
TEST(CenterNetOnnx, OpenCvDnnGivesTheBoxesOfLibtorch) {
  CenterNetConfig cfg;
  cfg.class_names = "red,blue";
  cfg.input_width = 96, cfg.input_height = 64;
  cfg.width = 8;
  cfg.epochs = 25;
  cfg.batch_size = 1;
  cfg.lr = 5e-3;
  cfg.score_threshold = 0.05;
  DetectionSample s;
  s.image = scene(120, 80);
  s.boxes = {{24, 20, 60, 40, 0, 1}, {64, 40, 112, 74, 1, 1}};
  CenterNet net(cfg);
  net.train({s}, {}, {}, {});  // trained a little: BatchNorm statistics that are not the identity
  cropsight::testing::TempDir t;
  net.export_onnx(t / "det.onnx");
  net.save(t / "det.pt");
  CenterNetOnnx onnx(t / "det.onnx");
  EXPECT_EQ(onnx.class_names(), net.class_names());
  EXPECT_EQ(onnx.config().input_width, 96);
  const ColorImage im = scene(150, 90);  // letterboxed
  const auto a = net.heads(im), b = onnx.heads(im);
  ASSERT_EQ(a.heatmap.size(), b.heatmap.size());
  float worst = 0;
  for (std::size_t i = 0; i < a.heatmap.size(); ++i) worst = std::max(worst, std::abs(a.heatmap[i] - b.heatmap[i]));
  for (std::size_t i = 0; i < a.size.size(); ++i) worst = std::max(worst, std::abs(a.size[i] - b.size[i]));
  for (std::size_t i = 0; i < a.mask.size(); ++i) worst = std::max(worst, std::abs(a.mask[i] - b.mask[i]));
  EXPECT_LT(worst, 1e-4f);
  // Boxes: every one of libtorch's five best has its twin from OpenCV (within 1e-3). (Weak peaks
  // of this briefly trained net can tie with a neighbour to within float rounding, so the full
  // lists may differ by such a peak.)
  const auto da = net.detect(im), db = onnx.detect(im);
  ASSERT_GE(da.size(), 2u);
  for (std::size_t i = 0; i < std::min<std::size_t>(5, da.size()); ++i) {
    bool twin = false;
    for (const auto& d : db)
      twin = twin || (d.class_id == da[i].class_id && std::abs(d.x1 - da[i].x1) < 1e-3f &&
                      std::abs(d.y1 - da[i].y1) < 1e-3f && std::abs(d.x2 - da[i].x2) < 1e-3f &&
                      std::abs(d.y2 - da[i].y2) < 1e-3f && std::abs(d.score - da[i].score) < 1e-3f);
    EXPECT_TRUE(twin) << "box " << i;
  }
  // load_center_detector picks the backend by extension.
  EXPECT_EQ(load_center_detector(t / "det.onnx")->detect({&im, nullptr}).size(), db.size());
  EXPECT_EQ(load_center_detector(t / "det.pt")->class_names(), net.class_names());

  // Flip test: both backends average with the mirrored image the same way (libtorch in one batch
  // of two, OpenCV DNN in two passes), and the setting travels in both files.
  net.set_flip_test(true);
  net.export_onnx(t / "flip.onnx");
  net.save(t / "flip.pt");
  CenterNetOnnx flip_onnx(t / "flip.onnx");
  EXPECT_TRUE(flip_onnx.config().flip_test);
  EXPECT_TRUE(CenterNet::load(t / "flip.pt", 1).config().flip_test);
  const auto fa = net.heads(im), fb = flip_onnx.heads(im);
  float flip_worst = 0, changed = 0;
  for (std::size_t i = 0; i < fa.mask.size(); ++i) {
    flip_worst = std::max(flip_worst, std::abs(fa.mask[i] - fb.mask[i]));
    changed = std::max(changed, std::abs(fa.mask[i] - a.mask[i]));
  }
  for (std::size_t i = 0; i < fa.heatmap.size(); ++i)
    flip_worst = std::max(flip_worst, std::abs(fa.heatmap[i] - fb.heatmap[i]));
  EXPECT_LT(flip_worst, 1e-4f);
  EXPECT_GT(changed, 1e-3f) << "the mirrored image's heads differ for this asymmetric scene";
  float offset_change = 0;  // offsets stay the unmirrored image's
  for (std::size_t i = 0; i < fa.offset.size(); ++i)
    offset_change = std::max(offset_change, std::abs(fa.offset[i] - a.offset[i]));
  EXPECT_LT(offset_change, 1e-5f);

  // Multi-scale mask test: both backends run the extra input (OpenCV DNN reshapes the graph) and
  // agree; the main heads are untouched, and the setting travels in both files.
  net.set_mask_inputs("128x96");
  net.export_onnx(t / "ms.onnx");
  net.save(t / "ms.pt");
  CenterNetOnnx ms_onnx(t / "ms.onnx");
  EXPECT_EQ(ms_onnx.config().mask_inputs, "128x96");
  EXPECT_EQ(CenterNet::load(t / "ms.pt", 1).config().mask_inputs, "128x96");
  const auto ma = net.heads(im), mb = ms_onnx.heads(im);
  ASSERT_EQ(ma.extra_masks.size(), 1u);
  ASSERT_EQ(mb.extra_masks.size(), 1u);
  EXPECT_EQ(ma.extra_masks[0].out_w, 32);
  EXPECT_EQ(ma.extra_masks[0].out_h, 24);
  ASSERT_EQ(ma.extra_masks[0].mask.size(), mb.extra_masks[0].mask.size());
  ASSERT_EQ(ma.extra_masks[0].mask.size(), 2u * 32u * 24u);
  float ms_worst = 0;
  for (std::size_t i = 0; i < ma.extra_masks[0].mask.size(); ++i)
    ms_worst = std::max(ms_worst, std::abs(ma.extra_masks[0].mask[i] - mb.extra_masks[0].mask[i]));
  EXPECT_LT(ms_worst, 1e-4f);
  EXPECT_EQ(ma.heatmap, fa.heatmap);  // the main input's heads are those without the extra pass
  // and the main pass still runs at the model's input after the graph was reshaped
  const auto again = ms_onnx.heads(im);
  for (std::size_t i = 0; i < again.heatmap.size(); ++i) EXPECT_NEAR(again.heatmap[i], fb.heatmap[i], 1e-5f);
  EXPECT_THROW(net.set_mask_inputs("100x96"), Error);

  // The extra passes without the flip test (mask_inputs_flip_test false): one pass each, still
  // the same in both backends, and no longer the flip-averaged scores.
  net.set_mask_inputs("128x96", false);
  net.export_onnx(t / "ms1.onnx");
  CenterNetOnnx ms1_onnx(t / "ms1.onnx");
  EXPECT_FALSE(ms1_onnx.config().mask_inputs_flip_test);
  EXPECT_TRUE(ms1_onnx.config().flip_test);
  const auto na = net.heads(im), nb = ms1_onnx.heads(im);
  ASSERT_EQ(na.extra_masks.size(), 1u);
  ASSERT_EQ(nb.extra_masks.size(), 1u);
  float one_worst = 0, one_changed = 0;
  for (std::size_t i = 0; i < na.extra_masks[0].mask.size(); ++i) {
    one_worst = std::max(one_worst, std::abs(na.extra_masks[0].mask[i] - nb.extra_masks[0].mask[i]));
    one_changed = std::max(one_changed, std::abs(na.extra_masks[0].mask[i] - ma.extra_masks[0].mask[i]));
  }
  EXPECT_LT(one_worst, 1e-4f);
  EXPECT_GT(one_changed, 1e-3f);
}

TEST(CenterNetOnnx, ForeignFilesAreNamed) {
  cropsight::testing::TempDir t;
  cropsight::testing::write_text(t / "junk.onnx", "junk");
  EXPECT_NE(onnx_error_of([&] { CenterNetOnnx x(t / "junk.onnx"); }).find("junk.onnx"), std::string::npos);
  EXPECT_NE(onnx_error_of([&] { CenterNetOnnx x(t / "none.onnx"); }).find("no such ONNX file"), std::string::npos);
  // A valid ONNX graph (Identity) without the detector's metadata: a foreign layout.
  onnx::ModelProto m;
  m.set_ir_version(7);
  m.add_opset_import()->set_version(11);
  auto* n = m.mutable_graph()->add_node();
  n->set_op_type("Identity");
  n->add_input("x");
  n->add_output("y");
  m.mutable_graph()->add_input()->set_name("x");
  m.mutable_graph()->add_output()->set_name("y");
  std::ofstream(t / "foreign.onnx", std::ios::binary) << m.SerializeAsString();
  const std::string e = onnx_error_of([&] { CenterNetOnnx x(t / "foreign.onnx"); });
  EXPECT_NE(e.find("foreign.onnx"), std::string::npos) << e;
  EXPECT_NE(e.find("foreign ONNX layout"), std::string::npos) << e;
}
#endif

}  // namespace

namespace {
// boxes_from_heads (center_decode.hpp), which the broccoli detector uses to get boxes and masks
// from one network run, decodes the heads exactly as detect() does: the shipped grape model (flip
// test on) on a synthetic image of another size than its input.
TEST(CenterNetOnnx, BoxesFromHeadsAreTheBoxesOfDetect) {
  using namespace cropsight;
  nn::CenterNetOnnx net(cropsight::testing::source_dir() / "models" / "detector-grape.onnx");
  ColorImage im(300, 200, Rgb8{60, 90, 50});
  for (int y = 40; y < 150; ++y)
    for (int x = 90; x < 170; ++x) im.at(x, y) = Rgb8{70, 30, 110};
  const auto from_heads = nn::boxes_from_heads(net.heads(im), net.config(), im.width, im.height);
  const auto detected = net.detect(im);
  ASSERT_FALSE(detected.empty()) << "the comparison needs boxes";
  ASSERT_EQ(from_heads.size(), detected.size());
  for (std::size_t i = 0; i < detected.size(); ++i) {
    EXPECT_EQ(from_heads[i].x1, detected[i].x1);
    EXPECT_EQ(from_heads[i].y2, detected[i].y2);
    EXPECT_EQ(from_heads[i].score, detected[i].score);
    EXPECT_EQ(from_heads[i].class_id, detected[i].class_id);
  }
}
}  // namespace
