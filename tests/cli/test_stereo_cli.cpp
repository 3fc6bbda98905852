// CLI tests of the seedling / stereo commands: stereo disparity, detect seedling,
// eval seedling and eval stereo, each on a success path and on error paths (missing file,
// mismatched image sizes): exit code 2, one line naming the input, and no output written.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "cropsight/stereo/stereo_io.hpp"
#include "seedling_cli_fixture.hpp"
#include "testing/testing.hpp"

namespace fs = std::filesystem;
using cropsight::testing::run_cli;
using cropsight::testing::shell_quoted;

namespace {

class StereoCli : public SeedlingCliFixture<StereoCli> {
 public:
  static constexpr const char* kSimulateArgs = " --pairs 2 --seed 77 --calib-pairs 0";

 protected:
  static void SetUpTestSuite() {
    SeedlingCliFixture::SetUpTestSuite();
    // A right image of another size than the simulated left one.
    cv::Mat small(240, 320, CV_8UC3, cv::Scalar(90, 120, 60));
    cv::imwrite((dir() / "small.png").string(), small);
  }
};

}  // namespace

TEST_F(StereoCli, DisparityWritesPngAndReportsFullCoverage) {
  const fs::path out = dir() / "disp.png";
  const auto r = run_cli("stereo disparity --left " + shell_quoted(pair0() / "left.png") + " --right " +
                         shell_quoted(pair0() / "right.png") + " --max-disp 64 --out " + shell_quoted(out) + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["method"], "sgm");
  EXPECT_DOUBLE_EQ(j["valid_percent"].get<double>(), 100.0);  // hole filling
  const cv::Mat d = cv::imread(out.string(), cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(d.empty());
  EXPECT_EQ(d.type(), CV_16U);
  EXPECT_EQ(d.cols, 640);
}

TEST_F(StereoCli, DisparityErrors) {
  const fs::path out = dir() / "never.png";
  auto r = run_cli("stereo disparity --left " + shell_quoted(dir() / "missing.png") + " --right " +
                   shell_quoted(pair0() / "right.png") + " --out " + shell_quoted(out));
  expect_one_line_error(r, "missing.png");
  r = run_cli("stereo disparity --left " + shell_quoted(pair0() / "left.png") + " --right " +
              shell_quoted(dir() / "small.png") + " --out " + shell_quoted(out));
  expect_one_line_error(r, "small.png");
  EXPECT_NE(r.err.find("differs"), std::string::npos) << r.err;
  r = run_cli("stereo disparity --left " + shell_quoted(pair0() / "left.png") + " --right " +
              shell_quoted(pair0() / "right.png") + " --max-disp 64 --set engine=fast --out " + shell_quoted(out));
  expect_one_line_error(r, "engine");
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(StereoCli, DetectSeedlingWritesResult) {
  const fs::path out = dir() / "result.json";
  const auto r = run_cli("detect seedling --left " + shell_quoted(pair0() / "left.png") + " --right " +
                         shell_quoted(pair0() / "right.png") + " --calib " + shell_quoted(data() / "rig.yaml") +
                         " --out " + shell_quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(std::ifstream(out));
  EXPECT_TRUE(j["found"].get<bool>());
  EXPECT_EQ(j["points"]["sampled"], 4096);
  EXPECT_GT(j["envelope"]["volume_m3"].get<double>(), 0.0);
  EXPECT_TRUE(j["timings_ms"].contains("total"));
}

TEST_F(StereoCli, DetectSeedlingErrors) {
  const fs::path out = dir() / "never.json";
  auto r = run_cli("detect seedling --left " + shell_quoted(pair0() / "left.png") + " --right " +
                   shell_quoted(pair0() / "right.png") + " --calib " + shell_quoted(dir() / "missing.yaml") +
                   " --out " + shell_quoted(out));
  expect_one_line_error(r, "missing.yaml");
  r = run_cli("detect seedling --left " + shell_quoted(pair0() / "left.png") + " --right " +
              shell_quoted(dir() / "small.png") + " --calib " + shell_quoted(data() / "rig.yaml") + " --out " +
              shell_quoted(out));
  expect_one_line_error(r, "small.png");
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(StereoCli, EvalSeedlingScoresPairs) {
  const auto r = run_cli("eval seedling --data " + shell_quoted(data()) + " --no-opencv --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["pairs"], 2);
  EXPECT_GE(j["recognition_rate"].get<double>(), 0.5);
  EXPECT_GT(j["sensitivity"].get<double>(), 0.5);
  EXPECT_NEAR(j["volume_ratio"].get<double>(), 1.0, 0.5);
  EXPECT_GT(j["ms_sgm"].get<double>(), 0.0);
}

TEST_F(StereoCli, EvalSeedlingErrors) {
  auto r = run_cli("eval seedling --data " + shell_quoted(dir() / "nowhere") + " --json");
  expect_one_line_error(r, "nowhere");
  EXPECT_TRUE(r.out.empty());
  // A pair whose right image has another size than its left one.
  const fs::path bad = dir() / "bad_pairs";
  fs::create_directories(bad / "pair_000");
  fs::copy_file(data() / "rig.yaml", bad / "rig.yaml", fs::copy_options::overwrite_existing);
  for (const char* f : {"left.png", "disparity.png", "mask.png", "truth.json"})
    fs::copy_file(pair0() / f, bad / "pair_000" / f, fs::copy_options::overwrite_existing);
  fs::copy_file(dir() / "small.png", bad / "pair_000" / "right.png", fs::copy_options::overwrite_existing);
  r = run_cli("eval seedling --data " + shell_quoted(bad) + " --no-opencv --json");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("pair_000"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
}

TEST_F(StereoCli, EvalStereoOnMiddlebury) {
  const auto mb = cropsight::testing::shared_data_dir() / "middlebury";
  CROPSIGHT_REQUIRE_DATA(mb);
  const auto r = run_cli("eval stereo --middlebury " + shell_quoted(mb) + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_LE(j["mean_bad1"].get<double>(), 8.0);
  EXPECT_LT(j["mean_bad1"].get<double>(), j["opencv_sgbm"]["mean_bad1"].get<double>());
  for (const char* p : {"tsukuba", "venus", "teddy", "cones"}) EXPECT_TRUE(j["pairs"].contains(p)) << p;
}

// --scenes: the shared 2005/2006 scenes (scene.yaml layout, range from the scene) and a written
// Middlebury 2014 folder with a right-view truth (non-occluded scores).
TEST_F(StereoCli, EvalStereoOnSceneFolders) {
  const auto mb = cropsight::testing::shared_data_dir() / "middlebury2006";
  CROPSIGHT_REQUIRE_DATA(mb);
  auto r = run_cli("eval stereo --scenes " + shell_quoted(mb) + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  for (const char* p : {"Aloe", "Baby1", "Cloth3", "Dolls"}) ASSERT_TRUE(j["pairs"].contains(p)) << p;
  EXPECT_EQ(j["pairs"]["Aloe"]["num_disparities"].get<int>(), 112);
  EXPECT_LT(j["mean_bad1"].get<double>(), j["opencv_sgbm"]["mean_bad1"].get<double>());
  EXPECT_FALSE(j.contains("mean_nonoccluded"));

  const fs::path s = dir() / "scenes2014" / "plane";
  fs::create_directories(s);
  cv::Mat left(40, 80, CV_8UC3), right;
  cv::randu(left, 0, 255);
  cv::GaussianBlur(left, left, cv::Size(3, 3), 0);
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, -4, 0, 1, 0);
  cv::warpAffine(left, right, shift, left.size(), cv::INTER_NEAREST, cv::BORDER_REPLICATE);
  cv::imwrite((s / "im0.png").string(), left);
  cv::imwrite((s / "im1.png").string(), right);
  cropsight::stereo::DisparityImage truth(80, 40, 4.0f);
  cropsight::stereo::write_pfm(s / "disp0GT.pfm", truth);
  cropsight::stereo::write_pfm(s / "disp1GT.pfm", truth);
  std::ofstream(s / "calib.txt") << "width=80\nheight=40\nndisp=16\n";
  r = run_cli("eval stereo --scenes " + shell_quoted(dir() / "scenes2014") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j["pairs"]["plane"].contains("nonoccluded")) << r.out;
  EXPECT_EQ(j["mean_nonoccluded"]["pairs"].get<int>(), 1);
  EXPECT_LT(j["pairs"]["plane"]["nonoccluded"]["bad1"].get<double>(), 5.0);
  // The text form prints one row per scene and the mean.
  r = run_cli("eval stereo --scenes " + shell_quoted(dir() / "scenes2014"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("plane"), std::string::npos);
  EXPECT_NE(r.out.find("mean"), std::string::npos);
}

TEST_F(StereoCli, EvalStereoErrors) {
  auto r = run_cli("eval stereo --middlebury " + shell_quoted(dir() / "no_middlebury") + " --json");
  expect_one_line_error(r, "no_middlebury");
  EXPECT_TRUE(r.out.empty());
  // Four pairs of the right names; tsukuba's right image has another size.
  const fs::path mb = dir() / "fake_middlebury";
  const cv::Mat img(48, 64, CV_8UC3, cv::Scalar(10, 20, 30)), narrow(48, 60, CV_8UC3, cv::Scalar(10, 20, 30));
  const cv::Mat gt(48, 64, CV_8U, cv::Scalar(40));
  for (const char* p : {"tsukuba", "venus", "teddy", "cones"}) {
    fs::create_directories(mb / p);
    cv::imwrite((mb / p / "left.png").string(), img);
    cv::imwrite((mb / p / "right.png").string(), std::string(p) == "tsukuba" ? narrow : img);
    const bool pgm = std::string(p) == "tsukuba" || std::string(p) == "venus";
    cv::imwrite((mb / p / (pgm ? "disp_left.pgm" : "disp_left.png")).string(), gt);
  }
  r = run_cli("eval stereo --middlebury " + shell_quoted(mb) + " --json");
  expect_one_line_error(r, "tsukuba");
  EXPECT_NE(r.err.find("differ"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
  // Neither folder option; a folder without scenes; a truncated PFM ground truth: one line
  // naming the folder or file, exit 2.
  r = run_cli("eval stereo --json");
  expect_one_line_error(r, "--scenes");
  r = run_cli("eval stereo --scenes " + shell_quoted(dir()) + "/no_scenes --json");
  expect_one_line_error(r, "no_scenes");
  const fs::path s = dir() / "bad_pfm" / "one";
  fs::create_directories(s);
  cv::imwrite((s / "im0.png").string(), img);
  cv::imwrite((s / "im1.png").string(), img);
  std::ofstream(s / "calib.txt") << "ndisp=16\n";
  std::ofstream(s / "disp0GT.pfm") << "Pf\n64 48\n-1\nshort";
  r = run_cli("eval stereo --scenes " + shell_quoted(dir() / "bad_pfm") + " --json");
  expect_one_line_error(r, "disp0GT.pfm");
  EXPECT_NE(r.err.find("truncated"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
}
