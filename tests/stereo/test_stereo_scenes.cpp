// PFM ground truths, scene folders (both layouts) and the non-occluded score, on tiny fixtures
// written by the tests themselves.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "cropsight/core/error.hpp"
#include "cropsight/stereo/middlebury.hpp"
#include "cropsight/stereo/stereo_io.hpp"
#include "cropsight/stereo/stereo_scenes.hpp"
#include "testing/testing.hpp"

using namespace cropsight;
using namespace cropsight::stereo;

namespace {

void expect_error_naming(const std::function<void()>& f, const std::string& what) {
  try {
    f();
    ADD_FAILURE() << "no error, expected one naming " << what;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
  }
}

// A 32x8 pair: the right view is the left one shifted by 2 px; truth 2 px everywhere.
ColorImage textured(int w, int h, int shift) {
  ColorImage im(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const auto v = std::uint8_t((((x + shift) * 37) ^ (y * 91)) & 255);
      im.at(x, y) = {v, v, v};
    }
  return im;
}

void write_pair(const std::filesystem::path& dir, const char* l, const char* r) {
  std::filesystem::create_directories(dir);
  write_color_png(dir / l, textured(32, 8, 0));
  write_color_png(dir / r, textured(32, 8, 2));
}

Image<float> constant(int w, int h, float v) {
  Image<float> im(w, h);
  for (float& f : im.data) f = v;
  return im;
}

}  // namespace

TEST(Pfm, RoundTripsBottomUpRowsAndUnknownValues) {
  cropsight::testing::TempDir tmp;
  Image<float> a(3, 2);
  a.at(0, 0) = 1.5f, a.at(1, 0) = 2.0f, a.at(2, 0) = INFINITY;
  a.at(0, 1) = 4.0f, a.at(1, 1) = 0.0f, a.at(2, 1) = 6.25f;
  write_pfm(tmp / "a.pfm", a);
  const Image<float> b = read_pfm(tmp / "a.pfm");
  ASSERT_EQ(b.width, 3);
  ASSERT_EQ(b.height, 2);
  EXPECT_FLOAT_EQ(b.at(0, 0), 1.5f);
  EXPECT_FLOAT_EQ(b.at(2, 1), 6.25f);
  EXPECT_TRUE(std::isnan(b.at(2, 0)));  // infinity = unknown
  // As a ground truth: 0 is unknown too, and the scale divides.
  const DisparityImage g = read_ground_truth(tmp / "a.pfm", 2.0);
  EXPECT_FLOAT_EQ(g.at(0, 1), 2.0f);
  EXPECT_TRUE(std::isnan(g.at(1, 1)));
  // A big-endian file (positive scale) is read too.
  {
    std::ofstream f(tmp / "be.pfm", std::ios::binary);
    f << "Pf\n1 1\n1.0\n";
    const unsigned char bytes[4] = {0x40, 0x49, 0x0f, 0xdb};  // 3.14159274 big-endian
    f.write(reinterpret_cast<const char*>(bytes), 4);
  }
  EXPECT_NEAR(read_pfm(tmp / "be.pfm").at(0, 0), 3.14159, 1e-5);
}

TEST(Pfm, BadFilesNameTheFile) {
  cropsight::testing::TempDir tmp;
  expect_error_naming([&] { read_pfm(tmp / "none.pfm"); }, "none.pfm");
  std::ofstream(tmp / "text.pfm") << "hello\n";
  expect_error_naming([&] { read_pfm(tmp / "text.pfm"); }, "not a PFM");
  std::ofstream(tmp / "colour.pfm") << "PF\n1 1\n-1\n";
  expect_error_naming([&] { read_pfm(tmp / "colour.pfm"); }, "colour");
  std::ofstream(tmp / "short.pfm") << "Pf\n4 4\n-1\nabcd";
  expect_error_naming([&] { read_pfm(tmp / "short.pfm"); }, "truncated");
  std::ofstream(tmp / "size.pfm") << "Pf\n0 4\n-1\n";
  expect_error_naming([&] { read_pfm(tmp / "size.pfm"); }, "size.pfm");
  // Fuzzing finding 30: a header claiming 19909 x 40242 floats in a 20-byte file allocated 3.2 GB
  // before the read found the data missing; the size is now checked against the file first.
  std::ofstream(tmp / "huge.pfm") << "Pf\n 19909\n 40242 4 9";
  expect_error_naming([&] { read_pfm(tmp / "huge.pfm"); }, "truncated");
  std::ofstream(tmp / "noscale.pfm") << "Pf\n2 2\n";
  expect_error_naming([&] { read_pfm(tmp / "noscale.pfm"); }, "noscale.pfm");
}

TEST(StereoScenes, LoadsBothLayoutsWithTheirRangesAndScales) {
  cropsight::testing::TempDir tmp;
  // Scene layout, 8-bit truth x 2, no right view.
  write_pair(tmp / "a", "left.png", "right.png");
  GrayImage gt(32, 8, 4);  // 2 px x scale 2
  gt.at(0, 0) = 0;         // unknown
  write_gray_png(tmp / "a" / "gt.png", gt);
  std::ofstream(tmp / "a" / "scene.yaml") << "gt_scale: 2\nmax_disparity: 20\n";
  // Middlebury 2014 layout with both views' truths: pixels whose partner falls outside the right
  // image are occluded.
  write_pair(tmp / "b", "im0.png", "im1.png");
  write_pfm(tmp / "b" / "disp0GT.pfm", constant(32, 8, 2.0f));
  write_pfm(tmp / "b" / "disp1GT.pfm", constant(32, 8, 2.0f));
  std::ofstream(tmp / "b" / "calib.txt") << "cam0=[1 0 0; 0 1 0; 0 0 1]\nwidth=32\nndisp=16\n";
  std::filesystem::create_directories(tmp / "not-a-scene");

  const auto scenes = load_stereo_scenes(tmp.path());
  ASSERT_EQ(scenes.size(), 2u);
  EXPECT_EQ(scenes[0].name, "a");
  EXPECT_EQ(scenes[0].num_disparities, 32);  // 20 rounded up to a multiple of 16, at most the width
  EXPECT_FLOAT_EQ(scenes[0].truth.at(5, 5), 2.0f);
  EXPECT_TRUE(std::isnan(scenes[0].truth.at(0, 0)));
  EXPECT_TRUE(scenes[0].nonoccluded.empty());
  EXPECT_EQ(scenes[1].name, "b");
  EXPECT_EQ(scenes[1].num_disparities, 16);
  ASSERT_FALSE(scenes[1].nonoccluded.empty());
  EXPECT_EQ(scenes[1].nonoccluded.at(0, 3), 0);  // x - d < 0: not seen by the right camera
  EXPECT_EQ(scenes[1].nonoccluded.at(10, 3), 255);

  // The evaluator scores both, the second also over its non-occluded pixels.
  const auto ev = evaluate_middlebury(scenes, [](const MiddleburyPair& p, int) {
    DisparityImage d = constant(p.truth.width, p.truth.height, 2.0f);
    d.at(1, 1) = NAN;   // a hole in the occluded strip (x < 2)
    d.at(20, 1) = 5.f;  // an error of 3 px on a visible pixel
    return d;
  });
  ASSERT_EQ(ev.pairs.size(), 2u);
  EXPECT_FALSE(ev.pairs[0].has_nonoccluded);
  ASSERT_TRUE(ev.pairs[1].has_nonoccluded);
  EXPECT_NEAR(ev.pairs[1].stats.bad1, 200.0 / 256, 1e-9);
  EXPECT_NEAR(ev.pairs[1].stats.invalid, 100.0 / 256, 1e-9);
  EXPECT_NEAR(ev.pairs[1].stats.avg_error, 3.0 / 255, 1e-6);
  EXPECT_NEAR(ev.pairs[1].nonoccluded.bad1, 100.0 / (256 - 16), 1e-9);
  EXPECT_EQ(ev.pairs[1].nonoccluded.invalid, 0.0);
  EXPECT_EQ(ev.nonoccluded_pairs, 1);
}

TEST(StereoScenes, BadScenesNameTheFile) {
  cropsight::testing::TempDir tmp;
  expect_error_naming([&] { load_stereo_scenes(tmp / "missing"); }, "missing");
  expect_error_naming([&] { load_stereo_scenes(tmp.path()); }, "no stereo scene");
  write_pair(tmp / "a", "left.png", "right.png");
  write_gray_png(tmp / "a" / "gt.png", GrayImage(32, 8, 4));
  std::ofstream(tmp / "a" / "scene.yaml") << "gt_scale: 2\n";
  expect_error_naming([&] { load_stereo_scenes(tmp.path()); }, "'max_disparity'");
  std::ofstream(tmp / "a" / "scene.yaml") << "gt_scale: -1\nmax_disparity: 16\n";
  expect_error_naming([&] { load_stereo_scenes(tmp.path()); }, "'gt_scale'");
  std::ofstream(tmp / "a" / "scene.yaml") << "gt_scale: 2\nmax_disparity: 16\n";
  write_gray_png(tmp / "a" / "gt.png", GrayImage(30, 8, 4));
  expect_error_naming([&] { load_stereo_scenes(tmp.path()); }, "gt.png");
  write_gray_png(tmp / "a" / "gt.png", GrayImage(32, 8, 0));
  expect_error_naming([&] { load_stereo_scenes(tmp.path()); }, "no valid pixel");
  std::filesystem::remove(tmp / "a" / "gt.png");
  std::ofstream(tmp / "a" / "gt.pfm") << "Pf\n32 8\n-1\n";
  expect_error_naming([&] { load_stereo_scenes(tmp.path()); }, "gt.pfm");
  write_pair(tmp / "b", "im0.png", "im1.png");
  write_pfm(tmp / "b" / "disp0GT.pfm", constant(32, 8, 2.0f));
  std::ofstream(tmp / "b" / "calib.txt") << "width=32\n";
  expect_error_naming([&] { load_stereo_scene(tmp / "b"); }, "ndisp");
}
