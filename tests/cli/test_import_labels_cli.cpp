// CLI tests of `cropsight import --coco / --labelme / --cvat`: labels drawn on a simulated
// sequence's frames become a sequence `train broccoli` trains on; an image set's labels become
// COCO, YOLO or VOC; every bad input is one line, exit 2, and nothing written.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>

#include "cropsight/io/files.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/io/voc.hpp"
#include "one_line_error.hpp"
#include "testing/testing.hpp"

namespace fs = std::filesystem;
using namespace cropsight;
using cropsight::testing::run_cli;
using cropsight::testing::shell_quoted;
using cropsight::testing::write_text;

namespace import_labels_cli_test {

// The bounding box of every instance of a label image, as a COCO box annotation of `category`.
nlohmann::json boxes_of(const LabelImage& labels, long image_id, long& next_id) {
  std::map<int, std::array<int, 4>> box;  // id → u0, v0, u1, v1 (inclusive)
  for (int v = 0; v < labels.height; ++v)
    for (int u = 0; u < labels.width; ++u) {
      const int id = labels.at(u, v);
      if (id == 0) continue;
      auto [it, fresh] = box.try_emplace(id, std::array<int, 4>{u, v, u, v});
      auto& b = it->second;
      b = {std::min(b[0], u), std::min(b[1], v), std::max(b[2], u), std::max(b[3], v)};
    }
  nlohmann::json out = nlohmann::json::array();
  for (const auto& [id, b] : box)
    out.push_back({{"id", ++next_id},
                   {"image_id", image_id},
                   {"category_id", 1},
                   {"bbox", {b[0], b[1], b[2] - b[0] + 1, b[3] - b[1] + 1}}});
  return out;
}

using cropsight::testing::expect_one_line_error;

}  // namespace import_labels_cli_test

using namespace import_labels_cli_test;

// Boxes of the simulator's own heads on frames 1 and 3 of a pass, written as a COCO file, imported
// onto the pass: two labelled frames with one instance per head, which train broccoli trains on.
TEST(ImportLabelsCli, CocoBoxesOntoASequenceTrainBroccoli) {
  cropsight::testing::TempDir t;
  ASSERT_EQ(run_cli("simulate broccoli --frames 5 --seed 31 --quiet --out " + shell_quoted(t / "seq")).exit_code, 0);
  const io::SequenceReader seq(t / "seq");
  nlohmann::json coco{{"images", nlohmann::json::array()},
                      {"annotations", nlohmann::json::array()},
                      {"categories", {{{"id", 1}, {"name", "head"}}}}};
  long next_id = 0;
  std::size_t heads = 0;
  for (int f : {1, 3}) {
    coco["images"].push_back({{"id", f + 10},
                              {"file_name", "color/" + io::frame_file_name(f)},
                              {"width", seq.info().camera.width},
                              {"height", seq.info().camera.height}});
    for (auto& a : boxes_of(seq.read(f).labels, f + 10, next_id)) coco["annotations"].push_back(a), ++heads;
  }
  ASSERT_GT(heads, 0u);
  write_text(t / "c.json", coco.dump());
  auto r = run_cli("import --coco " + shell_quoted(t / "c.json") + " --data " + shell_quoted(t / "seq") + " --out " +
                   shell_quoted(t / "lab") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["frames"], 2);
  EXPECT_EQ(j["instances"], heads);
  EXPECT_EQ(j["source_frames"], (std::vector<int>{1, 3}));
  EXPECT_EQ(io::SequenceReader(t / "lab").size(), 2);
  r = run_cli("train broccoli --data " + shell_quoted(t / "lab") + " --config broccoli-oes-uk --quiet --json --out " +
              shell_quoted(t / "m.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["frames"], 2);
}

TEST(ImportLabelsCli, ImageSetsBecomeCocoYoloOrVoc) {
  cropsight::testing::TempDir t;
  write_text(t / "c.xml", R"(<annotations><image id="0" name="imgs/a.jpg" width="20" height="10">
    <box label="potato" xtl="2" ytl="2" xbr="6" ybr="4"/><polygon label="stone" points="10,1;14,1;14,5"/></image>
    <image id="1" name="imgs/b.jpg" width="20" height="10"/></annotations>)");
  const std::string base = "import --cvat " + shell_quoted(t / "c.xml");
  auto r = run_cli(base + " --out " + shell_quoted(t / "a.json") + " --classes potato --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto coco = nlohmann::json::parse(io::read_file(t / "a.json"));
  EXPECT_EQ(coco["images"].size(), 2u);
  EXPECT_EQ(coco["annotations"].size(), 1u) << "only the potato";
  EXPECT_EQ(coco["categories"][0]["name"], "potato");
  r = run_cli(base + " --to yolo --out " + shell_quoted(t / "yolo"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(io::read_file(t / "yolo" / "a.txt"), "0 0.2 0.3 0.2 0.2\n1 0.6 0.3 0.2 0.4\n");
  EXPECT_EQ(io::read_file(t / "yolo" / "b.txt"), "");
  EXPECT_EQ(io::read_file(t / "yolo" / "classes.txt"), "potato\nstone\n");
  r = run_cli(base + " --to voc --out " + shell_quoted(t / "voc"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto voc = io::read_voc(t / "voc" / "a.xml");
  ASSERT_EQ(voc.objects.size(), 2u);
  EXPECT_EQ(voc.objects[1].name, "stone");
  EXPECT_DOUBLE_EQ(voc.objects[1].xmax, 14);
}

TEST(ImportLabelsCli, BadInputIsOneLineAndWritesNothing) {
  cropsight::testing::TempDir t;
  write_text(t / "bad.json", "{\"images\": [");
  write_text(t / "ok.json", R"({"images": [{"id": 1, "file_name": "x/a.png", "width": 4, "height": 4},
    {"id": 2, "file_name": "y/a.png", "width": 4, "height": 4}], "categories": [], "annotations": []})");
  const std::string out = " --out " + shell_quoted(t / "out");
  expect_one_line_error(run_cli("import --coco " + shell_quoted(t / "bad.json") + out), "bad.json");
  expect_one_line_error(run_cli("import --coco " + shell_quoted(t / "ok.json") + " --cvat x.xml" + out), "exactly one");
  expect_one_line_error(run_cli("import --coco " + shell_quoted(t / "ok.json") + " --to yolo" + out), "a.png");
  expect_one_line_error(
      run_cli("import --coco " + shell_quoted(t / "ok.json") + " --data " + shell_quoted(t / "noseq") + out), "noseq");
  expect_one_line_error(run_cli("import --labelme " + shell_quoted(t / "nolm") + out), "nolm");
  EXPECT_FALSE(fs::exists(t / "out"));
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(t.path())) ++entries;
  EXPECT_EQ(entries, 2u) << "no temporary left beside the inputs";
}
