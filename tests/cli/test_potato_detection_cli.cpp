// detect potato / eval potato-detection end to end: the paper's metric from its own detection
// files, a detection round trip on a synthetic image with a known potato, and every bad input
// as one stderr line naming the file and exit 2 (no partial output left).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "cropsight/io/voc.hpp"
#include "cropsight/pipeline/potato/detection_eval.hpp"
#include "testing/testing.hpp"

namespace {
namespace fs = std::filesystem;
using cropsight::testing::CommandResult;
using cropsight::testing::run_cli;
using cropsight::testing::shell_quoted;
using cropsight::testing::TempDir;

fs::path detection_dir() { return cropsight::testing::shared_data_dir() / "potato" / "detection"; }

void expect_error(const CommandResult& r, const std::string& what) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(what), std::string::npos) << "expected '" << what << "' in: " << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

using cropsight::testing::write_text;

// One 200x200 image with one potato-coloured ellipse (box [70, 130] x [50, 150]) and its VOC file.
void synthetic_set(const fs::path& dir) {
  fs::create_directories(dir / "images");
  fs::create_directories(dir / "ann");
  cv::Mat lab(1, 1, CV_8UC3, cv::Scalar(110, 134.38, 150.98)), bgr;
  cv::cvtColor(lab, bgr, cv::COLOR_Lab2BGR);
  cv::Mat m(200, 200, CV_8UC3, cv::Scalar(240, 235, 235));
  cv::ellipse(m, {100, 100}, {30, 50}, 0, 0, 360, cv::Scalar(bgr.at<cv::Vec3b>(0, 0)), cv::FILLED);
  cv::imwrite((dir / "images" / "a.png").string(), m);
  write_text(dir / "ann" / "a.xml",
             "<annotation><filename>a.png</filename><object><name>potato</name><bndbox><xmin>70</xmin><ymin>50</ymin>"
             "<xmax>130</xmax><ymax>150</ymax></bndbox></object></annotation>");
}

TEST(PotatoDetectionCli, ScoresThePapersDetections) {
  CROPSIGHT_REQUIRE_DATA(detection_dir());
  const fs::path dets = detection_dir() / "paper_detections" / "ssd300_mobilenet";
  const auto r =
      run_cli("eval potato-detection --images " + shell_quoted(detection_dir() / "images") + " --annotations " +
              shell_quoted(detection_dir() / "annotations_voc") + " --detections " + shell_quoted(dets) + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto set = cropsight::pipeline::potato::load_annotated_images(detection_dir() / "images",
                                                                      detection_dir() / "annotations_voc");
  const auto lib = cropsight::pipeline::potato::evaluate_saved_detections(set, dets);
  EXPECT_DOUBLE_EQ(j["ap50"].get<double>(), lib.ap.ap50);
  EXPECT_DOUBLE_EQ(j["ap75"].get<double>(), lib.ap.ap75);
  EXPECT_DOUBLE_EQ(j["map50_95"].get<double>(), lib.ap.map50_95);
  EXPECT_NEAR(j["ap50"].get<double>(), 0.875, 1e-9);  // 28 of 32 found, no false positive above them
  EXPECT_EQ(j["images"], 11);
  EXPECT_EQ(j["boxes"], 32);
}

TEST(PotatoDetectionCli, DetectWritesBoxesThatEvalScores) {
  TempDir t;
  synthetic_set(t.path());
  const auto r = run_cli("detect potato --images " + shell_quoted(t / "images") + " --out " + shell_quoted(t / "out") +
                         " --overlay " + shell_quoted(t / "ov") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto all = nlohmann::json::parse(r.out);  // one object: every image's detections
  ASSERT_EQ(all["images"].size(), 1u);
  const auto& j = all["images"][0];
  EXPECT_EQ(j["image"], "a.png");
  ASSERT_EQ(j["detections"].size(), 1u);
  const auto lines = cropsight::io::read_detection_text(t / "out" / "a.txt");
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0].label, "potato");
  EXPECT_NEAR(lines[0].x1, 70, 2);
  EXPECT_NEAR(lines[0].y2, 151, 2);
  EXPECT_TRUE(fs::exists(t / "ov" / "a.png"));
  const auto e = run_cli("eval potato-detection --images " + shell_quoted(t / "images") + " --annotations " +
                         shell_quoted(t / "ann") + " --detections " + shell_quoted(t / "out") + " --json");
  ASSERT_EQ(e.exit_code, 0) << e.err;
  EXPECT_EQ(nlohmann::json::parse(e.out)["ap50"].get<double>(), 1.0);
}

TEST(PotatoDetectionCli, BadInputsAreOneLineNamingTheFile) {
  TempDir t;
  synthetic_set(t.path());
  // Undecodable image: nothing written to --out.
  fs::create_directories(t / "bad_images");
  write_text(t / "bad_images" / "broken.jpg", "not a jpeg");
  expect_error(run_cli("detect potato --images " + shell_quoted(t / "bad_images") + " --out " + shell_quoted(t / "o1")),
               "broken.jpg");
  EXPECT_FALSE(fs::exists(t / "o1"));
  // Unknown --set key.
  expect_error(run_cli("detect potato --images " + shell_quoted(t / "images") + " --out " + shell_quoted(t / "o2") +
                       " --set detector.classical.colour=1"),
               "detector.classical.colour");
  // Malformed XML.
  fs::create_directories(t / "bad_ann");
  write_text(t / "bad_ann" / "a.xml", "<annotation><object>");
  expect_error(run_cli("eval potato-detection --images " + shell_quoted(t / "images") + " --annotations " +
                       shell_quoted(t / "bad_ann")),
               "a.xml: malformed XML");
  // A detection file with a bad line.
  fs::create_directories(t / "bad_dets");
  write_text(t / "bad_dets" / "a.txt", "potato 0.9 70 50 130 150\npotato 0.8 70 50 x 150\n");
  expect_error(run_cli("eval potato-detection --images " + shell_quoted(t / "images") + " --annotations " +
                       shell_quoted(t / "ann") + " --detections " + shell_quoted(t / "bad_dets")),
               "a.txt: line 2: x2 is not a number");
  // A missing image folder.
  expect_error(run_cli("detect potato --images " + shell_quoted(t / "nowhere") + " --out " + shell_quoted(t / "o3")),
               "nowhere");
}

TEST(PotatoDetectionCli, DetectReadsOneImageOrASequenceAndDrawsAxes) {
  TempDir t;
  synthetic_set(t.path());
  // One image file: its boxes, and in the JSON object each box's length axis (the ellipse is 100 px
  // tall and 60 px wide, so the axis is vertical: pi / 2).
  const auto one = run_cli("detect potato --images " + shell_quoted(t / "images" / "a.png") + " --out " +
                           shell_quoted(t / "one") + " --overlay " + shell_quoted(t / "ov") + " --json");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const auto all = nlohmann::json::parse(one.out);
  ASSERT_EQ(all["images"].size(), 1u) << one.out;
  const auto& j = all["images"][0];
  ASSERT_EQ(j["detections"].size(), 1u) << one.out;
  EXPECT_NEAR(j["detections"][0]["angle"].get<double>(), M_PI / 2, 0.05);
  EXPECT_TRUE(fs::exists(t / "one" / "a.txt"));
  // The overlay has the box (green) and the axis (red) drawn on it.
  const cv::Mat ov = cv::imread((t / "ov" / "a.png").string());
  ASSERT_FALSE(ov.empty());
  const cv::Vec3b axis = ov.at<cv::Vec3b>(100, 100);  // BGR: the axis crosses the centre
  EXPECT_GT(axis[2], 200);
  EXPECT_LT(axis[1], 60);

  // A simulated RGB-D sequence: one text file per colour frame, named after it, and depth reaches
  // the detector.
  const fs::path seq = t / "seq";
  ASSERT_EQ(run_cli("simulate potato --frames 3 --seed 77 --out " + shell_quoted(seq)).exit_code, 0);
  const auto r = run_cli("detect potato --data " + shell_quoted(seq) + " --out " + shell_quoted(t / "sd"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  int files = 0, boxes = 0;
  for (const auto& e : fs::directory_iterator(t / "sd")) {
    if (e.path().filename() == ".cropsight-output") continue;  // the output marker (docs/cli.md)
    ++files;
    std::ifstream in(e.path());
    for (std::string line; std::getline(in, line);) boxes += line.rfind("potato ", 0) == 0 ? 1 : 0;
  }
  EXPECT_EQ(files, 3);
  EXPECT_GE(boxes, 3) << "the simulated approach has a potato in view in every frame";

  // Exactly one input; a foreign --model file is one line naming it.
  expect_error(run_cli("detect potato --out " + shell_quoted(t / "n1")), "exactly one of --images and --data");
  expect_error(run_cli("detect potato --images " + shell_quoted(t / "images") + " --data " + shell_quoted(seq) +
                       " --out " + shell_quoted(t / "n2")),
               "exactly one of --images and --data");
  write_text(t / "fake.onnx", "not an onnx graph");
  expect_error(run_cli("detect potato --images " + shell_quoted(t / "images") + " --model " +
                       shell_quoted(t / "fake.onnx") + " --out " + shell_quoted(t / "n3")),
               "fake.onnx");
  for (const char* o : {"n1", "n2", "n3"}) EXPECT_FALSE(fs::exists(t / o)) << o;
}

}  // namespace
