// Each system's chapter opening on the demo page, read from a small folder laid out as the demo
// writes it (the whole demo, opened in Chromium, is tests/cli/test_demo_page.cpp).
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "cropsight/core/error.hpp"
#include "cropsight/io/grape_text.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/report/demo_page.hpp"
#include "testing/testing.hpp"

using namespace cropsight;
using namespace cropsight::report;
namespace fs = std::filesystem;

namespace {

int occurrences_of(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

std::string figures_text(const SystemSummary& s) {
  std::string t;
  for (const auto& [what, value] : s.figures) t += what + " = " + value + "\n";
  return t;
}

void write_json(const fs::path& path, const nlohmann::json& j) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << j.dump();
}

}  // namespace

TEST(DemoSections, AMissingFileIsNamedWithTheCommandThatWritesIt) {
  cropsight::testing::TempDir dir;
  const std::string seedling = cropsight::testing::error_message([&] { seedling_summary(dir.path()); });
  EXPECT_NE(seedling.find("detect.json"), std::string::npos) << seedling;
  EXPECT_NE(seedling.find("detect seedling"), std::string::npos) << seedling;
  const std::string potato = cropsight::testing::error_message([&] { potato_summary(dir.path()); });
  EXPECT_NE(potato.find("targets.jsonl"), std::string::npos) << potato;
  const std::string grape = cropsight::testing::error_message([&] { grape_summary(dir.path()); });
  EXPECT_NE(grape.find("truth.json"), std::string::npos) << grape;
  const std::string det = cropsight::testing::error_message([&] { detector_summary(dir.path()); });
  EXPECT_NE(det.find("images"), std::string::npos) << det;
}

TEST(DemoSections, PotatoSummaryShowsTheMiddleTargetInFullView) {
  cropsight::testing::TempDir dir;
  CameraIntrinsics cam;
  cam.width = 64, cam.height = 48, cam.fx = cam.fy = 50, cam.cx = 31.5, cam.cy = 23.5;
  fs::create_directories(dir / "data" / "color");
  io::write_camera_yaml(dir / "data" / "camera.yaml", cam);
  io::write_color(dir / "data" / "color" / "000001.png", ColorImage(64, 48, {200, 200, 190}));
  const auto msg = [](int frame, bool cut) {
    return nlohmann::json{{"frame", frame},   {"detection", true}, {"depth_ok", true}, {"cut", cut},
                          {"angle_ok", true}, {"x", 0.01},         {"y", -0.02},       {"z", 0.4},
                          {"width", 0.05},    {"height", 0.07},    {"angle", 0.5},     {"box", {20, 10, 40, 30}}};
  };
  std::ofstream(dir / "targets.jsonl") << msg(0, true).dump() << "\n" << msg(1, false).dump() << "\n";
  write_json(dir / "harvest.json", {{"fps", 40.0}});
  write_json(dir / "eval.json",
             {{"frames_positioned", 1},
              {"position", {{"x", {{"mae_mm", 1.0}}}, {"y", {{"mae_mm", 2.0}}}, {"z", {{"mae_mm", 3.0}}}}}});
  const SystemSummary s = potato_summary(dir.path());
  const std::string f = figures_text(s);
  EXPECT_NE(f.find("frame 1 = 10, -20, 400 mm"), std::string::npos) << f;  // not the cut frame 0
  EXPECT_NE(f.find("= 50 × 70 mm"), std::string::npos) << f;
  EXPECT_NE(f.find("= 1.0 / 2.0 / 3.0 mm"), std::string::npos) << f;
  EXPECT_EQ(occurrences_of(s.picture_svg, "<rect"), 1);
  EXPECT_EQ(s.commands.size(), 3u);  // no commands.txt: the generic ones
}

TEST(DemoSections, GrapeSummaryScoresTheLabelsAndFindsTheCutPoint) {
  cropsight::testing::TempDir dir;
  Cloud c;
  for (int i = 0; i < 300; ++i) {
    const int label = i < 30 ? 2 : 1 + (i % 5 == 0 ? 2 : 0);  // 30 peduncle points, berries, leaves
    const float x = label == 2 ? 0.001f * float(i % 5) : 0.002f * float(i % 17);
    const float y = label == 2 ? -0.05f - 0.001f * float(i / 5) : 0.002f * float(i / 17);
    c.points.emplace_back(x, y, 0.5f);
    c.normals.emplace_back(0, 0, -1);
    c.colors.emplace_back(0.1f, 0.1f, 0.1f);
    c.labels.push_back(label);
  }
  fs::create_directories(dir / "data");
  io::write_grape_text(dir / "data" / "cloud.txt", c);
  io::write_grape_text(dir / "labelled.txt", c);  // a perfect segmenter
  Eigen::Vector3f cut = Eigen::Vector3f::Zero();
  for (int i = 0; i < 30; ++i) cut += c.points[std::size_t(i)] / 30.f;
  write_json(dir / "data" / "truth.json", {{"centroid_m", {0, 0, 0}},
                                           {"scale_m", 1.0},
                                           {"to_camera_rotation", {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}},
                                           {"cut_point", {{"position_m", {cut.x(), cut.y(), cut.z()}}}}});
  write_json(dir / "segment.json", {{"ms", 12.0}});
  std::ofstream(dir / "commands.txt") << "cropsight simulate grape --seed 3 --out X\n\ncropsight segment grape ...\n";
  const SystemSummary s = grape_summary(dir.path());
  const std::string f = figures_text(s);
  EXPECT_NE(f.find("= 1.000 / "), std::string::npos) << f;  // OAcc
  EXPECT_NE(f.find("0 mm from the true one"), std::string::npos) << f;
  EXPECT_NE(s.picture_svg.find("simulator&#39;s labels"), std::string::npos);  // escaped
  EXPECT_EQ(s.commands,
            (std::vector<std::string>{"cropsight simulate grape --seed 3 --out X", "cropsight segment grape ..."}));
}

TEST(DemoSections, DetectorSummaryDrawsTheShownBoxesAndCountsTheCoveredTruth) {
  cropsight::testing::TempDir dir;
  fs::create_directories(dir / "images");
  fs::create_directories(dir / "labels");
  io::write_color(dir / "images" / "a.png", ColorImage(64, 48, {120, 120, 120}));
  LabelImage labels(64, 48);
  for (int v = 10; v < 30; ++v)
    for (int u = 10; u < 30; ++u) labels.at(u, v) = 3;
  labels.at(60, 40) = 4;  // a sliver: no object to find
  io::write_u16(dir / "labels" / "a.png", labels);
  write_json(dir / "objects" / "detections.json",
             nlohmann::json::array({{{"file_name", "a.png"}, {"bbox", {10, 10, 19, 19}}, {"score", 0.8}},
                                    {{"file_name", "a.png"}, {"bbox", {40, 5, 10, 10}}, {"score", 0.1}},
                                    {{"file_name", "b.png"}, {"bbox", {0, 0, 5, 5}}, {"score", 0.9}}}));
  write_json(dir / "detect.json", {{"images", 1}, {"ms_per_image", 12.5}});
  const SystemSummary s = detector_summary(dir.path());
  const std::string f = figures_text(s);
  EXPECT_NE(f.find("a.png = 1 of 2"), std::string::npos) << f;
  EXPECT_NE(f.find("IoU ≥ 0.5 = 1 of 1"), std::string::npos) << f;
  EXPECT_NE(f.find("= 12 ms"), std::string::npos) << f;
  EXPECT_EQ(occurrences_of(s.picture_svg, "<rect"), 2);  // the shown box and the dashed truth
  HtmlPage page("d");
  add_demo_chapters(page, {.detector = dir.path()});
  EXPECT_EQ(occurrences_of(page.html(), "<article class=\"system\""), 1);
}
