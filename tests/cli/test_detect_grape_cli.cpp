// `detect grape` end to end through the CLI binary on the synthetic vine frame of
// tests/pipeline/grape/grape_test_frame.hpp, with boxes from a COCO file and from the shipped
// detector (skipped until the CLI is built).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "cropsight/io/cloud_io.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/sequence.hpp"
#include "pipeline/grape/grape_test_frame.hpp"
#include "testing/testing.hpp"

namespace {
namespace fs = std::filesystem;
using cropsight::testing::run_cli;
using cropsight::testing::shell_quoted;

// The frame's three files and its boxes as a COCO results array, in `dir`; returns the
// arguments that name them.
std::string write_grape_frame(const fs::path& dir) {
  const auto t = cropsight::testing::grape_test_frame();
  cropsight::io::write_u16(dir / "depth.png", t.frame.depth);
  cropsight::io::write_color(dir / "color.png", t.frame.color);
  cropsight::io::write_camera_yaml(dir / "camera.yaml", t.frame.camera);
  nlohmann::json boxes = nlohmann::json::array();
  for (const auto& d : t.boxes)
    boxes.push_back({{"image_id", 0},
                     {"category_id", d.category},
                     {"bbox", {d.box.x, d.box.y, d.box.width, d.box.height}},
                     {"score", d.score}});
  cropsight::testing::write_text(dir / "boxes.json", boxes.dump());
  return " --color " + shell_quoted(dir / "color.png") + " --depth " + shell_quoted(dir / "depth.png") + " --camera " +
         shell_quoted(dir / "camera.yaml");
}

TEST(DetectGrapeCli, BoxesFileGivesLabelledBunchesAndCutPoints) {
  if (!fs::exists(cropsight::testing::cli_path())) GTEST_SKIP() << "CLI not built";
  cropsight::testing::TempDir t;
  const std::string frame = write_grape_frame(t.path());
  const fs::path models = cropsight::testing::source_dir() / "models", out = t / "out";
  const std::string to = "detect grape" + frame + " --detections " + shell_quoted(t / "boxes.json") + " --segmenter " +
                         shell_quoted(models / "grape-gbdt-fast.json") + " --threads 1 --out ";
  const std::string args = to + shell_quoted(out);
  auto r = run_cli(args + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto file = nlohmann::json::parse(cropsight::io::read_file(out / "cut_points.json"));
  EXPECT_EQ(j["bunches"], file["bunches"]);
  EXPECT_EQ(j["detections"], 4);
  EXPECT_EQ(j["boxes_from"], "detections");
  ASSERT_EQ(file["bunches"].size(), 2u);  // bunch A (with its peduncle), B and C merged
  EXPECT_EQ(file["bunches"][0]["roi"], (std::vector<int>{60, 33, 41, 63}));
  EXPECT_EQ(file["bunches"][1]["roi"], (std::vector<int>{120, 70, 34, 29}));
  for (const auto& b : file["bunches"]) {
    const auto cloud = cropsight::io::read_cloud(out / b["file"].get<std::string>());
    EXPECT_EQ(cloud.size(), b["points"].get<std::size_t>());
    ASSERT_EQ(cloud.labels.size(), cloud.size());
    long total = 0;
    for (long n : b["label_counts"].get<std::vector<long>>()) total += n;
    EXPECT_EQ(total, long(cloud.size()));
    for (const auto& p : cloud.points) EXPECT_TRUE(p.z() > 0.6f && p.z() < 1.51f) << p.z();  // metres
    // A cut point is null or a full object (what the model labels peduncle decides which).
    const auto& cut = b["cut_point"];
    if (!cut.is_null()) {
      EXPECT_EQ(cut["position_m"].size(), 3u);
      EXPECT_LE(cut["direction"][1].get<double>(), 0.0);  // up in the image
      EXPECT_GE(cut["confidence"].get<int>(), 10);
    }
  }
  // The shipped models label no peduncle on this frame; taking the label they give most points
  // of bunch A (1-5) as "peduncle" exercises the cut point's JSON: a region of a few hundred
  // neighbouring pixels (5 mm apart at 0.8 m) is one cluster at 1 cm.
  const auto counts = file["bunches"][0]["label_counts"].get<std::vector<long>>();
  const long most = std::max_element(counts.begin() + 1, counts.end()) - counts.begin();
  ASSERT_GE(counts[std::size_t(most)], 100) << "the model labels bunch A almost all 0";
  r = run_cli(to + shell_quoted(t / "out-l") + " --json --set cut_point.peduncle_label=" + std::to_string(most));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto cut = nlohmann::json::parse(r.out)["bunches"][0]["cut_point"];
  ASSERT_TRUE(cut.is_object()) << cut;
  const auto dir = cut["direction"].get<std::vector<double>>();
  ASSERT_EQ(dir.size(), 3u);
  EXPECT_NEAR(std::hypot(dir[0], dir[1], dir[2]), 1.0, 1e-5);
  EXPECT_LE(dir[1], 0.0);
  EXPECT_GE(cut["confidence"].get<long>(), 10);
  EXPECT_LE(cut["confidence"].get<long>(), counts[std::size_t(most)]);
  const auto pos = cut["position_m"].get<std::vector<double>>();
  ASSERT_EQ(pos.size(), 3u);
  EXPECT_TRUE(pos[2] > 0.6 && pos[2] < 1.51) << pos[2];  // metres, in front of the camera
  // A second run replaces the folder (with --force); one with another tool's file in it is refused, untouched.
  const std::string again = args + " --force";
  r = run_cli(again);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  cropsight::testing::write_text(out / "notes.txt", "mine\n");
  r = run_cli(again);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("which cropsight did not write"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(out / "notes.txt") && fs::exists(out / "cut_points.json"));
  // A cut-point key out of range names the key; no boxes source at all is a usage error.
  r = run_cli(to + shell_quoted(t / "out2") + " --set cut_point.min_points=1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("'cut_point.min_points'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(t / "out2"));
  r = run_cli("detect grape" + frame + " --out " + shell_quoted(t / "out3"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--detector"), std::string::npos) << r.err;
}

TEST(DetectGrapeCli, ShippedDetectorRuns) {
  if (!fs::exists(cropsight::testing::cli_path())) GTEST_SKIP() << "CLI not built";
  const fs::path models = cropsight::testing::source_dir() / "models";
  if (!fs::exists(models / "detector-grape.onnx")) GTEST_SKIP() << "shipped detector absent";
  cropsight::testing::TempDir t;
  const std::string frame = write_grape_frame(t.path());
  const auto r = run_cli("detect grape" + frame + " --detector " + shell_quoted(models / "detector-grape.onnx") +
                         " --segmenter " + shell_quoted(models / "grape-gbdt-fast.json") + " --threads 1 --out " +
                         shell_quoted(t / "out") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["boxes_from"], "detector");
  EXPECT_TRUE(j["bunches"].is_array());
  EXPECT_EQ(nlohmann::json::parse(cropsight::io::read_file(t / "out" / "cut_points.json"))["bunches"], j["bunches"]);
  // The shipped model by name: detector.backend (auto: libtorch where the plugin is built) picks
  // the runtime; the same weights find the same boxes.
  for (const char* backend : {"auto", "opencv"}) {
    const auto named = run_cli("detect grape" + frame + " --detector detector-grape --set detector.backend=" + backend +
                               " --segmenter " + shell_quoted(models / "grape-gbdt-fast.json") + " --threads 1 --out " +
                               shell_quoted(t / (std::string("named-") + backend)) + " --json");
    ASSERT_EQ(named.exit_code, 0) << named.err;
    EXPECT_EQ(nlohmann::json::parse(named.out)["detections"], j["detections"]) << backend;
  }
}

}  // namespace
