// Our census SGM (src/stereo/census_sgm.cpp) against OpenCV's StereoSGBM on the same inputs,
// its AVX2 kernel against its portable one, and its left-right check on a known occlusion.
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <random>

#include "core/cpu_dispatch.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/stereo/disparity.hpp"
#include "cropsight/stereo/middlebury.hpp"
#include "stereo/census_sgm.hpp"
#include "stereo/cv_convert.hpp"
#include "testing/testing.hpp"

using namespace cropsight;
using namespace cropsight::stereo;

namespace {

// Smoothed random texture, 8-bit.
cv::Mat texture_mat(int w, int h, unsigned seed) {
  cv::Mat noise(h / 2 + 1, w / 2 + 1, CV_8U), big;
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 256);
  cv::resize(noise, big, cv::Size(w, h), 0, 0, cv::INTER_LINEAR);
  return big;
}

// Background plane at disparity 9 with a fronto-parallel square at disparity 23 in front of it.
// Returns left, right and the true left disparity (NaN where the left pixel is occluded in the
// right view or its partner lies outside the right image).
struct Scene {
  cv::Mat left, right;
  cv::Mat truth;  // CV_32F
};
Scene two_planes(int w, int h) {
  const int dbg = 9, dfg = 23;
  const cv::Mat bg = texture_mat(w + 64, h, 11), fg = texture_mat(w + 64, h, 12);
  const int x0 = w / 3, x1 = w / 3 + w / 4, y0 = h / 4, y1 = 3 * h / 4;  // square in the left view
  auto in_square = [&](int x, int y) { return x >= x0 && x < x1 && y >= y0 && y < y1; };
  Scene s;
  s.left.create(h, w, CV_8U);
  s.right.create(h, w, CV_8U);
  s.truth.create(h, w, CV_32F);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      // Texture is attached to the surfaces: surface coordinate u = x_left.
      s.left.at<std::uint8_t>(y, x) = in_square(x, y) ? fg.at<std::uint8_t>(y, x) : bg.at<std::uint8_t>(y, x + 32);
      // Right pixel xr sees the square when xr + dfg falls in it, else the background at xr + dbg.
      const int xf = x + dfg;
      s.right.at<std::uint8_t>(y, x) =
          in_square(xf, y) ? fg.at<std::uint8_t>(y, xf) : bg.at<std::uint8_t>(y, std::min(x + dbg + 32, w + 63));
      float t = in_square(x, y) ? float(dfg) : float(dbg);
      // Background left pixels hidden behind the square in the right view are occluded.
      if (!in_square(x, y) && in_square(x - dbg + dfg, y)) t = std::nanf("");
      if (!std::isnan(t) && x - int(t) < 0) t = std::nanf("");  // int(NaN) is undefined (UBSan)
      s.truth.at<float>(y, x) = t;
    }
  return s;
}

DisparityImage plain_sgbm(const cv::Mat& l, const cv::Mat& r, int nd) {
  // OpenCV's sample parameters (block 3, P1 = 8 bs², P2 = 32 bs², grey), no padding or filling.
  auto sgbm = cv::StereoSGBM::create(0, nd, 3, 8 * 9, 32 * 9, 1, 63, 10, 100, 32, cv::StereoSGBM::MODE_SGBM);
  cv::Mat d16;
  sgbm->compute(l, r, d16);
  DisparityImage out(l.cols, l.rows, std::nanf(""));
  for (int y = 0; y < l.rows; ++y)
    for (int x = 0; x < l.cols; ++x) {
      const short v = d16.at<short>(y, x);
      if (v >= 0) out.at(x, y) = float(v) / 16.0f;
    }
  return out;
}

struct Agreement {
  long both = 0, within1 = 0;
  double rate() const { return both ? double(within1) / double(both) : 0.0; }
};
Agreement agree(const DisparityImage& a, const DisparityImage& b) {
  Agreement g;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::isnan(a.data[i]) || std::isnan(b.data[i])) continue;
    ++g.both;
    g.within1 += std::fabs(a.data[i] - b.data[i]) <= 1.0f;
  }
  return g;
}

}  // namespace

TEST(CensusSgm, AgreesWithOpenCvSgbmOnTexturedTwoPlaneScene) {
  const Scene s = two_planes(320, 240);
  stereo::detail::CensusSgmParams p;
  p.num_disparities = 48;
  const DisparityImage ours = stereo::detail::census_sgm(s.left, s.right, p);
  const DisparityImage cv = plain_sgbm(s.left, s.right, 48);
  const Agreement g = agree(ours, cv);
  EXPECT_GT(g.both, 320L * 240 / 2);  // both produce estimates on most of the image
  EXPECT_GE(g.rate(), 0.98) << g.within1 << " of " << g.both;
  // And both are right where the truth is known.
  long ok = 0, n = 0;
  for (int y = 0; y < 240; ++y)
    for (int x = 0; x < 320; ++x) {
      const float t = s.truth.at<float>(y, x), e = ours.at(x, y);
      if (std::isnan(t) || std::isnan(e)) continue;
      ++n;
      ok += std::fabs(e - t) <= 1.0f;
    }
  EXPECT_GE(double(ok) / double(n), 0.98);
  EXPECT_GE(double(n) / (320.0 * 240.0), 0.80);
}

TEST(CensusSgm, LeftRightCheckRejectsOcclusion) {
  const Scene s = two_planes(320, 240);
  stereo::detail::CensusSgmParams p;
  p.num_disparities = 48;
  const DisparityImage ours = stereo::detail::census_sgm(s.left, s.right, p);
  // The background strip just left of the square (14 px wide) is visible only in the left view.
  long occluded = 0, rejected = 0;
  for (int y = 70; y < 170; ++y)
    for (int x = 0; x < 320; ++x) {
      if (!std::isnan(s.truth.at<float>(y, x)) || x < 48) continue;
      ++occluded;
      const float e = ours.at(x, y);
      rejected += std::isnan(e) || std::fabs(e - 9.0f) <= 1.0f;  // no wrong foreground value
    }
  ASSERT_GT(occluded, 1000);
  EXPECT_GE(double(rejected) / double(occluded), 0.9);
}

TEST(CensusSgm, Avx2KernelEqualsPortableKernel) {
  if (!cropsight::detail::cpu_has_avx2_fma()) GTEST_SKIP() << "CPU without AVX2";
  const Scene s = two_planes(200, 120);
  // 9x7 (64-bit census, scalar popcount) and 5x5 (32-bit census, vectorised popcount).
  for (int cw : {9, 5}) {
    stereo::detail::CensusSgmParams p;
    p.num_disparities = 32;
    p.census_width = cw;
    p.census_height = cw == 9 ? 7 : 5;
    p.p2_step = 4;
    p.cost_box = cw == 9 ? 3 : 1;  // and the horizontal cost box
    const DisparityImage a = stereo::detail::census_sgm(s.left, s.right, p);
    p.allow_avx2 = false;
    const DisparityImage b = stereo::detail::census_sgm(s.left, s.right, p);
    ASSERT_EQ(a.size(), b.size());
    long valid = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      ASSERT_EQ(std::isnan(a.data[i]), std::isnan(b.data[i])) << i;
      if (!std::isnan(a.data[i])) {
        ASSERT_EQ(a.data[i], b.data[i]) << i;
        ++valid;
      }
    }
    EXPECT_GT(valid, long(a.size()) / 2);
  }
}

TEST(CensusSgm, RejectsBadInput) {
  const cv::Mat a = texture_mat(64, 48, 1), b = texture_mat(60, 48, 2);
  stereo::detail::CensusSgmParams p;
  p.num_disparities = 16;
  EXPECT_THROW(stereo::detail::census_sgm(a, b, p), Error);
  p.num_disparities = 24;
  EXPECT_THROW(stereo::detail::census_sgm(a, a, p), Error);
  p.num_disparities = 16;
  p.census_width = 11;  // 11 x 7 > 64 bits
  EXPECT_THROW(stereo::detail::census_sgm(a, a, p), Error);
}

TEST(CensusSgm, AgreesWithOpenCvSgbmOnMiddleburyCones) {
  const auto dir = cropsight::testing::shared_data_dir() / "middlebury";
  CROPSIGHT_REQUIRE_DATA(dir);
  for (const auto& pair : load_middlebury(dir)) {
    if (pair.name != "cones") continue;
    cv::Mat l, r;
    cv::cvtColor(stereo::detail::view(pair.left), l, cv::COLOR_RGB2GRAY);
    cv::cvtColor(stereo::detail::view(pair.right), r, cv::COLOR_RGB2GRAY);
    stereo::detail::CensusSgmParams p;
    p.num_disparities = 64;
    const DisparityImage ours = stereo::detail::census_sgm(l, r, p);
    const DisparityImage cv = plain_sgbm(l, r, 64);
    const Agreement g = agree(ours, cv);
    EXPECT_GT(g.both, long(pair.left.size()) / 2);
    EXPECT_GE(g.rate(), 0.90) << g.within1 << " of " << g.both;
    // Ours, unfilled, is at least as accurate as OpenCV's on the pixels both estimate.
    long ok_ours = 0, ok_cv = 0, n = 0;
    for (std::size_t i = 0; i < ours.size(); ++i) {
      const float t = pair.truth.data[i];
      if (std::isnan(t) || std::isnan(ours.data[i]) || std::isnan(cv.data[i])) continue;
      ++n;
      ok_ours += std::fabs(ours.data[i] - t) <= 1.0f;
      ok_cv += std::fabs(cv.data[i] - t) <= 1.0f;
    }
    EXPECT_GE(ok_ours, ok_cv * 99 / 100) << "of " << n;
  }
}
