#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <opencv2/imgproc.hpp>
#include <random>

#include "cropsight/core/error.hpp"
#include "cropsight/io/config_yaml.hpp"
#include "cropsight/sim/seedling/seedling_sim.hpp"
#include "cropsight/stereo/calibration.hpp"
#include "cropsight/stereo/disparity.hpp"
#include "cropsight/stereo/middlebury.hpp"
#include "cropsight/stereo/reconstruct.hpp"
#include "testing/testing.hpp"

using namespace cropsight;
using namespace cropsight::stereo;

namespace {
// Random blob texture (smoothed noise) of size w x h.
GrayImage texture(int w, int h, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<float> coarse(std::size_t(w / 3 + 2) * (h / 3 + 2));
  for (auto& v : coarse) v = float(rng() % 256);
  GrayImage g(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float fx = x / 3.0f, fy = y / 3.0f;
      const int ix = int(fx), iy = int(fy);
      const float tx = fx - ix, ty = fy - iy;
      const int cw = w / 3 + 2;
      auto c = [&](int a, int b) { return coarse[std::size_t(b) * cw + a]; };
      const float v = (1 - ty) * ((1 - tx) * c(ix, iy) + tx * c(ix + 1, iy)) +
                      ty * ((1 - tx) * c(ix, iy + 1) + tx * c(ix + 1, iy + 1));
      g.at(x, y) = std::uint8_t(std::clamp(v + float(rng() % 9) - 4.0f, 0.0f, 255.0f));
    }
  return g;
}
}  // namespace

TEST(Disparity, FrontoParallelPlaneIsExact) {
  const int w = 320, h = 240, d = 12;
  const GrayImage wide = texture(w + d, h, 5);
  GrayImage left(w, h), right(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      left.at(x, y) = wide.at(x, y);  // left(x) = right(x - d): disparity d everywhere
      right.at(x, y) = wide.at(x + d, y);
    }
  DisparityConfig cfg;
  cfg.num_disparities = 32;
  const DisparityImage est = compute_disparity(left, right, cfg);
  long exact = 0, valid = 0;
  for (float v : est.data) {
    valid += std::isfinite(v);
    exact += std::fabs(v - float(d)) < 0.25f;
  }
  EXPECT_EQ(valid, long(w) * h);  // hole filling: every pixel has an estimate
  EXPECT_GE(double(exact) / double(w * h), 0.995);
}

// fill_disparity_holes runs its median in two row blocks on two threads, each with the rows of
// context it needs: the filled pixels must equal one cv::medianBlur over the whole scan-line
// filled image, and matched pixels must stay as they were.
TEST(Disparity, HoleFillingMedianEqualsOneOpenCvMedianOverTheImage) {
  const int w = 97, h = 151;  // odd sizes; more than two 32-row grains, so the rows are split
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> value(0.0f, 60.0f);
  DisparityImage in(w, h, 0.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      in.row(y)[x] = (rng() % 10 < 3 || y == 40 || y == 75 || y == 76) ? std::nanf("") : value(rng);
  for (int k : {3, 5}) {
    DisparityImage scanline = in, filled = in;
    fill_disparity_holes(scanline, 0);
    fill_disparity_holes(filled, k);
    cv::Mat reference;
    cv::medianBlur(cv::Mat(h, w, CV_32F, scanline.data.data()), reference, k);
    long holes = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const float original = in.row(y)[x], got = filled.row(y)[x];
        if (std::isnan(original)) {
          ++holes;
          ASSERT_EQ(got, reference.at<float>(y, x)) << "k " << k << " at " << x << "," << y;
        } else {
          ASSERT_EQ(got, original) << "k " << k << " at " << x << "," << y;
        }
      }
    EXPECT_GT(holes, long(w) * h / 4);
  }
}

TEST(Disparity, RejectsMismatchedSizesAndBadConfig) {
  const GrayImage a = texture(64, 48, 1), b = texture(60, 48, 2);
  DisparityConfig cfg;
  cfg.num_disparities = 16;
  EXPECT_THROW(compute_disparity(a, b, cfg), Error);
  cfg.num_disparities = 20;  // not a multiple of 16
  EXPECT_THROW(compute_disparity(a, a, cfg), Error);
  EXPECT_THROW(block_matching(a, b, 16, 55, BlockCost::kSad), Error);
}

TEST(Disparity, BlockMatchingFindsPlane) {
  const int w = 200, h = 120, d = 7;
  const GrayImage wide = texture(w + d, h, 9);
  GrayImage left(w, h), right(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) left.at(x, y) = wide.at(x, y), right.at(x, y) = wide.at(x + d, y);
  const auto est = block_matching(left, right, 16, 15, BlockCost::kSsd);
  EXPECT_FLOAT_EQ(est.at(100, 60), float(d));
  EXPECT_TRUE(std::isnan(est.at(2, 2)));  // window leaves the image
}

namespace {
// Corner observations of a known rig: pinhole projection of the board corners + 0.1 px noise.
void observe(const Eigen::Matrix3d& K, const Eigen::Matrix3d& R, const Eigen::Vector3d& T, int views,
             const Checkerboard& board, std::vector<std::vector<Eigen::Vector2f>>& l,
             std::vector<std::vector<Eigen::Vector2f>>& r) {
  std::mt19937 rng(4);
  std::normal_distribution<double> noise(0, 0.1);
  std::uniform_real_distribution<double> u(-1, 1);
  while (int(l.size()) < views) {
    const Eigen::Matrix3d Rb = (Eigen::AngleAxisd(0.5 * u(rng), Eigen::Vector3d::UnitX()) *
                                Eigen::AngleAxisd(0.5 * u(rng), Eigen::Vector3d::UnitY()) *
                                Eigen::AngleAxisd(0.3 * u(rng), Eigen::Vector3d::UnitZ()))
                                   .toRotationMatrix();
    const Eigen::Vector3d tb(0.1 * u(rng) - 0.12, 0.08 * u(rng) - 0.07, 0.55 + 0.2 * u(rng));
    std::vector<Eigen::Vector2f> a, b;
    bool ok = true;
    for (const auto& p : board.object_points()) {
      const Eigen::Vector3d xl = Rb * p.cast<double>() + tb, xr = R * xl + T;
      const Eigen::Vector3d pl = K * xl, pr = K * xr;
      a.emplace_back(float(pl.x() / pl.z() + noise(rng)), float(pl.y() / pl.z() + noise(rng)));
      b.emplace_back(float(pr.x() / pr.z() + noise(rng)), float(pr.y() / pr.z() + noise(rng)));
      for (const auto& q : {a.back(), b.back()}) ok = ok && q.x() > 0 && q.y() > 0 && q.x() < 639 && q.y() < 479;
    }
    if (ok) l.push_back(a), r.push_back(b);
  }
}
}  // namespace

TEST(Calibration, RecoversKnownRig) {
  Eigen::Matrix3d K;
  K << 420, 0, 322, 0, 420, 238, 0, 0, 1;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.02, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Vector3d T(-0.06, 0.001, 0.0005);
  Checkerboard board;
  std::vector<std::vector<Eigen::Vector2f>> l, r;
  observe(K, R, T, 12, board, l, r);
  const auto c = calibrate_stereo(l, r, board, 640, 480, CalibrationConfig{});
  EXPECT_LT(c.rms, 0.3);
  EXPECT_NEAR(c.baseline(), T.norm(), 0.01 * T.norm());
  EXPECT_NEAR(c.K1(0, 0), 420, 4.2);
  EXPECT_NEAR(c.K2(1, 1), 420, 4.2);
  EXPECT_LT((c.R - R).norm(), 5e-3);

  // Save / load round trip.
  cropsight::testing::TempDir tmp;
  save_calibration(tmp / "calib.yaml", c);
  const auto back = load_calibration(tmp / "calib.yaml");
  EXPECT_NEAR(back.baseline(), c.baseline(), 1e-9);
  EXPECT_NEAR((back.F - c.F).norm(), 0, 1e-9 * c.F.norm() + 1e-15);
}

// A key that is a list was read as "" ("unknown key ''"); now it names the line (io::detail::yaml_key).
TEST(Calibration, KeyThatIsAListNamesItsLine) {
  cropsight::testing::TempDir tmp;
  std::ofstream(tmp / "c.yaml") << "image_width: 640\n[K1]: 1\n";
  try {
    load_calibration(tmp / "c.yaml");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("line 2: a key must be a plain name, not a list"), std::string::npos)
        << e.what();
  }
}

TEST(Calibration, TooFewViewsIsAClearError) {
  Eigen::Matrix3d K;
  K << 420, 0, 320, 0, 420, 240, 0, 0, 1;
  Checkerboard board;
  std::vector<std::vector<Eigen::Vector2f>> l, r;
  observe(K, Eigen::Matrix3d::Identity(), Eigen::Vector3d(-0.06, 0, 0), 2, board, l, r);
  try {
    calibrate_stereo(l, r, board, 640, 480, CalibrationConfig{});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("too few checkerboard views"), std::string::npos) << e.what();
  }
}

TEST(Calibration, MissingKeyIsAClearError) {
  cropsight::testing::TempDir tmp;
  std::ofstream(tmp / "c.yaml") << "image_width: 640\nimage_height: 480\nK1: [1,0,0,0,1,0,0,0,1]\n";
  try {
    load_calibration(tmp / "c.yaml");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("missing key 'K2'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("c.yaml"), std::string::npos);
  }
}

TEST(Calibration, RenderedCheckerboardsGiveTheSimulatedRig) {
  sim::SeedlingSimConfig cfg;
  sim::StereoRigModel rig = cfg.rig();
  const auto poses = sim::random_board_poses(rig, 9, 6, 0.03, 6, 3);
  ASSERT_EQ(poses.size(), 6u);
  Checkerboard board;
  std::vector<std::vector<Eigen::Vector2f>> l, r;
  for (const auto& [R, t] : poses) {
    const auto pair = sim::render_checkerboard_pair(rig, 9, 6, 0.03, R, t, 2);
    std::vector<Eigen::Vector2f> a, b;
    if (find_corners(pair.left, board, a) && find_corners(pair.right, board, b)) l.push_back(a), r.push_back(b);
  }
  ASSERT_GE(l.size(), 4u);
  CalibrationConfig cc;
  const auto c = calibrate_stereo(l, r, board, rig.width, rig.height, cc);
  EXPECT_LT(c.rms, 0.5);
  EXPECT_NEAR(c.baseline(), 0.06, 0.0006);
}

TEST(Middlebury, MeanBad1AtMostEightPercent) {
  const auto dir = cropsight::testing::shared_data_dir() / "middlebury";
  CROPSIGHT_REQUIRE_DATA(dir);
  const auto pairs = load_middlebury(dir);
  double ours = 0, plain = 0;
  for (const auto& p : pairs) {
    DisparityConfig cfg;
    cfg.num_disparities = ((p.max_disparity + 1 + 15) / 16) * 16;
    ours += bad_pixels(compute_disparity(p.left, p.right, cfg), p.truth).bad1;
    plain += bad_pixels(opencv_sgbm_disparity(p.left, p.right, cfg.num_disparities), p.truth).bad1;
  }
  EXPECT_LE(ours / 4, 8.0);
  EXPECT_LT(ours, plain);  // and clearly better than plain SGBM under the holes-are-errors rule
}

TEST(Reconstruct, DepthFromDisparity) {
  DisparityImage d(4, 2, std::nanf(""));
  d.at(2, 1) = 10.0f;
  d.at(0, 0) = -1.0f;
  RectifiedGeometry g{4, 2, 500, 1.5, 0.5, 1.5, 0.06};
  const auto sp = reconstruct(d, g);
  ASSERT_EQ(sp.points.size(), 1u);
  EXPECT_NEAR(sp.points[0].z(), 500 * 0.06 / 10, 1e-6);
  EXPECT_NEAR(sp.points[0].x(), (2 - 1.5) * 3.0 / 500, 1e-6);
  EXPECT_EQ(sp.pixels[0], 1 * 4 + 2);
}
