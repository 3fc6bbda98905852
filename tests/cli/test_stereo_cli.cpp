// CLI tests of the seedling / stereo commands (issue 5): stereo disparity, detect seedling,
// eval seedling and eval stereo, each on a success path and on error paths (missing file,
// mismatched image sizes): exit code 2, one line naming the input, and no output written.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

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
}
