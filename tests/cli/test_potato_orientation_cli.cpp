// eval potato-orientation end to end on a synthetic set in the paper's folder layout: one potato
// drawn at a known angle on a white board, its colourised depth (red = near) beside it. The summary
// and the per-shot list (--shots) agree with the drawn angles; bad input is one line naming the
// file, exit 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "cropsight/pipeline/potato/blob_detector.hpp"
#include "testing/testing.hpp"

namespace {
namespace fs = std::filesystem;
using cropsight::testing::run_cli;
using cropsight::testing::shell_quoted;
using cropsight::testing::TempDir;

// One shot: `angle_deg` trigonometric (counter-clockwise as the image is viewed). cv::ellipse turns
// clockwise as viewed (y down), hence the minus sign.
void draw_shot(const fs::path& root, int angle_deg, int number) {
  const std::string a = std::to_string(angle_deg);
  fs::create_directories(root / "rgb" / (a + "_high_rgb"));
  fs::create_directories(root / "depth" / (a + "_high_depth"));
  const std::string name = "image" + std::to_string(number) + ".png";
  const cropsight::pipeline::potato::BlobConfig model;  // the shipped colour model's mean
  cv::Mat lab(1, 1, CV_8UC3, cv::Scalar(110, model.mean_a, model.mean_b)), skin;
  cv::cvtColor(lab, skin, cv::COLOR_Lab2BGR);
  cv::Mat rgb(480, 640, CV_8UC3, cv::Scalar(225, 228, 230));  // BGR: a white board
  cv::ellipse(rgb, {320, 240}, {60, 38}, -angle_deg, 0, 360, cv::Scalar(skin.at<cv::Vec3b>(0, 0)), cv::FILLED);
  cv::imwrite((root / "rgb" / (a + "_high_rgb") / name).string(), rgb);
  cv::Mat depth(480, 640, CV_8UC3, cv::Scalar(160, 40, 0));                                         // BGR: far = blue
  cv::ellipse(depth, {320, 240}, {60, 38}, -angle_deg, 0, 360, cv::Scalar(0, 0, 230), cv::FILLED);  // near = red
  cv::imwrite((root / "depth" / (a + "_high_depth") / name).string(), depth);
}

std::string command(const fs::path& root, const std::string& input, const std::string& boxes = "detector") {
  return "eval potato-orientation --color " + shell_quoted(root / "rgb") + " --depth " + shell_quoted(root / "depth") +
         " --modality " + input + " --boxes " + boxes + " --shots --json";
}
}  // namespace

TEST(PotatoOrientationCli, ShotsListTheDrawnAngles) {
  TempDir tmp;
  draw_shot(tmp.path(), 30, 1);
  draw_shot(tmp.path(), 120, 2);
  for (const std::string boxes : {"detector", "board"})
    for (const char* input : {"depth", "rgb"}) {
      SCOPED_TRACE(boxes);
      const auto r = run_cli(command(tmp.path(), input, boxes));
      ASSERT_EQ(r.exit_code, 0) << r.err;
      const auto j = nlohmann::json::parse(r.out);
      EXPECT_EQ(j["count"], 2) << input;
      EXPECT_EQ(j["failures"], 0) << input;
      ASSERT_EQ(j["shots"].size(), 2u) << input;
      double sum = 0;
      for (const auto& s : j["shots"]) {
        EXPECT_TRUE(s["ok"].get<bool>()) << input;
        const double truth = s["truth_deg"], estimate = s["estimate_deg"], error = s["error_deg"];
        EXPECT_TRUE(truth == 30.0 || truth == 120.0) << truth;
        EXPECT_LT(error, 2.0) << input << " " << truth;
        EXPECT_NEAR(std::abs(estimate - truth), error, 1e-6) << input;  // no wrap-around at these angles
        EXPECT_NE(s["file"].get<std::string>().find(input == std::string("depth") ? "_depth" : "_rgb"),
                  std::string::npos);
        sum += error;
      }
      EXPECT_NEAR(j["mae_deg"].get<double>(), sum / 2, 1e-6) << input;
      EXPECT_NE(j["boxes"].get<std::string>().find(boxes == "board" ? "BoardBlob" : "potato preset"),
                std::string::npos);
    }
  // Without --shots there is no list.
  const auto plain = run_cli("eval potato-orientation --color " + shell_quoted(tmp.path() / "rgb") + " --depth " +
                             shell_quoted(tmp.path() / "depth") + " --json");
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_FALSE(nlohmann::json::parse(plain.out).contains("shots"));
  EXPECT_NE(nlohmann::json::parse(plain.out)["boxes"].get<std::string>().find("BoardBlob"), std::string::npos);
}

TEST(PotatoOrientationCli, BadInputIsOneLineNamingTheFile) {
  TempDir tmp;
  draw_shot(tmp.path(), 30, 1);
  const fs::path depth = tmp.path() / "depth" / "30_high_depth" / "image1.png";
  // A depth image that is not an image.
  cropsight::testing::write_text(depth, "not a png");
  auto r = run_cli(command(tmp.path(), "depth"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("image1.png"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  // An unknown box source.
  r = run_cli(command(tmp.path(), "rgb", "oracle"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--boxes"), std::string::npos) << r.err;
  // No depth partner at all.
  fs::remove(depth);
  r = run_cli(command(tmp.path(), "depth"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("image1.png"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}
