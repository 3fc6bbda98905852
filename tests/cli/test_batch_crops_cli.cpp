// cropsight batch for the crops whose results are per frame (potato, grape, seedling): each shard
// writes its rows, the batch concatenates them with the recording in front and sums them per
// recording; frame-range shards keep each frame's row once; a bad recording fails before any work.
#include <nlohmann/json.hpp>

#include "batch_fixture.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/sequence.hpp"
#include "pipeline/grape/grape_test_frame.hpp"

namespace cropsight::batch_test {

namespace batch_crops_test {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

fs::path crop_manifest(const fs::path& file, const std::vector<fs::path>& recordings, const std::string& pipeline,
                       const std::string& extra = "") {
  std::string list;
  for (const fs::path& p : recordings) list += (list.empty() ? "" : ", ") + ("'" + p.string() + "'");
  cropsight::testing::write_text(file, "recordings: [" + list + "]\npipeline: " + pipeline + "\n" + extra);
  return file;
}

// Two frames of the synthetic vine as an RGB-D sequence, with their boxes in detections.json.
void write_grape_sequence(const fs::path& dir) {
  const auto t = cropsight::testing::grape_test_frame();
  fs::create_directories(dir / "depth");
  fs::create_directories(dir / "color");
  io::write_camera_yaml(dir / "camera.yaml", t.frame.camera);
  nlohmann::json boxes = nlohmann::json::array();
  for (int i = 0; i < 2; ++i) {
    char name[16];
    std::snprintf(name, sizeof name, "%06d.png", i);
    io::write_u16(dir / "depth" / name, t.frame.depth);
    io::write_color(dir / "color" / name, t.frame.color);
    for (const auto& d : t.boxes)
      boxes.push_back({{"image_id", i},
                       {"category_id", d.category},
                       {"bbox", {d.box.x, d.box.y, d.box.width, d.box.height}},
                       {"score", d.score}});
  }
  cropsight::testing::write_text(dir / "detections.json", boxes.dump());
}

}  // namespace batch_crops_test
using namespace batch_crops_test;

TEST(BatchCrops, PotatoFrameRangesKeepEveryFrameOnceAndSumPerRecording) {
  cropsight::testing::TempDir tmp;
  for (int seed : {3, 4})
    ASSERT_EQ(run_cli("simulate potato --quiet --frames 10 --seed " + std::to_string(seed) + " --out " +
                      shell_quoted(tmp / ("potato-" + std::to_string(seed))))
                  .exit_code,
              0);
  const std::vector<fs::path> recs{tmp / "potato-3", tmp / "potato-4"};
  // Whole recordings, then ranges of 4 frames with a 2-frame overlap: every frame's row once, in
  // order, with the same detections (the tracker's ids restart per range: they may differ).
  const auto whole =
      run_cli("batch --json --manifest " + shell_quoted(crop_manifest(tmp / "m.yaml", recs, "{crop: potato}")) +
              " --out " + shell_quoted(tmp / "whole"));
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  const auto rows = lines_of(slurp(tmp / "whole" / "targets.csv"));
  ASSERT_EQ(rows.size(), 21u);  // header + 2 × 10 frames
  EXPECT_EQ(rows[0].rfind("recording,shard,frame,timestamp_s,detections,", 0), 0u) << rows[0];
  EXPECT_EQ(rows[1].rfind("potato-3,potato-3,0,", 0), 0u) << rows[1];
  EXPECT_EQ(rows[20].rfind("potato-4,potato-4,9,", 0), 0u) << rows[20];
  const auto passes = lines_of(slurp(tmp / "whole" / "passes.csv"));
  ASSERT_EQ(passes.size(), 3u);
  EXPECT_EQ(passes[1].rfind("potato-3,1,10,", 0), 0u) << passes[1];
  EXPECT_NE(slurp(tmp / "whole" / "report.html").find("targets selected per recording"), std::string::npos);

  const auto ranged = run_cli("batch --json --manifest " +
                              shell_quoted(crop_manifest(tmp / "r.yaml", recs, "{crop: potato}",
                                                         "shards: {frames_per_shard: 4, overlap_frames: 2}\n")) +
                              " --out " + shell_quoted(tmp / "ranged") + " --workers 2");
  ASSERT_EQ(ranged.exit_code, 0) << ranged.err;
  EXPECT_EQ(json_number(ranged.out, "ran"), 6);  // 3 ranges a recording
  const auto ranged_rows = lines_of(slurp(tmp / "ranged" / "targets.csv"));
  ASSERT_EQ(ranged_rows.size(), rows.size());
  const auto fields = [](const std::string& row) {
    std::vector<std::string> f;
    std::stringstream in(row);
    for (std::string x; std::getline(in, x, ',');) f.push_back(x);
    return f;
  };
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const auto a = fields(rows[i]), b = fields(ranged_rows[i]);
    ASSERT_GE(b.size(), 5u);
    EXPECT_EQ(b[0] + " " + b[2] + " " + b[3] + " " + b[4], a[0] + " " + a[2] + " " + a[3] + " " + a[4]) << i;
  }
  EXPECT_EQ(fields(ranged_rows[5])[1], "potato-3-f000004");
}

TEST(BatchCrops, SeedlingPairsOneRowEach) {
  cropsight::testing::TempDir tmp;
  for (int seed : {1, 2})
    ASSERT_EQ(run_cli("simulate seedling --pairs 2 --calib-pairs 0 --seed " + std::to_string(seed) + " --out " +
                      shell_quoted(tmp / ("seedling-" + std::to_string(seed))))
                  .exit_code,
              0);
  const auto r = run_cli(
      "batch --json --manifest " +
      shell_quoted(crop_manifest(tmp / "m.yaml", {tmp / "seedling-1", tmp / "seedling-2"}, "{crop: seedling}")) +
      " --out " + shell_quoted(tmp / "out"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = lines_of(slurp(tmp / "out" / "seedlings.csv"));
  ASSERT_EQ(rows.size(), 5u);
  EXPECT_EQ(rows[0],
            "recording,shard,pair_index,pair,found,length_m,width_m,height_m,volume_m3,top_view_area_m2,points");
  EXPECT_EQ(rows[1].rfind("seedling-1,seedling-1,0,pair_", 0), 0u) << rows[1];
  // Simulated seedlings are found, about ten centimetres long.
  for (std::size_t i = 1; i < rows.size(); ++i) {
    std::vector<std::string> f;
    std::stringstream in(rows[i]);
    for (std::string x; std::getline(in, x, ',');) f.push_back(x);
    ASSERT_EQ(f.size(), 11u) << rows[i];
    EXPECT_EQ(f[4], "1") << rows[i];
    EXPECT_GT(std::stod(f[5]), 0.03) << rows[i];
    EXPECT_LT(std::stod(f[5]), 0.3) << rows[i];
  }
}

TEST(BatchCrops, GrapeBoxesFromEachRecordingsDetectionsFile) {
  cropsight::testing::TempDir tmp;
  write_grape_sequence(tmp / "vine-a");
  write_grape_sequence(tmp / "vine-b");
  const fs::path m = crop_manifest(tmp / "m.yaml", {tmp / "vine-a", tmp / "vine-b"},
                                   "{crop: grape, model: grape-gbdt-fast, sets: {segmenter.threads: 1}}");
  const auto r = run_cli("batch --json --manifest " + shell_quoted(m) + " --out " + shell_quoted(tmp / "out"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = lines_of(slurp(tmp / "out" / "bunches.csv"));
  ASSERT_EQ(rows.size(), 9u);  // header + 2 recordings × 2 frames × 2 bunches (B and C merge)
  EXPECT_EQ(rows[0].rfind("recording,shard,frame,bunch,roi_x,", 0), 0u) << rows[0];
  EXPECT_EQ(rows[1].substr(rows[1].find(",0,0,") + 5), rows[3].substr(rows[3].find(",1,0,") + 5))
      << "the same frame twice gives the same bunch";
  // A recording without detections.json and no detector: refused before any shard runs.
  fs::remove(tmp / "vine-b" / "detections.json");
  const auto bad = run_cli("batch --manifest " + shell_quoted(m) + " --out " + shell_quoted(tmp / "bad"));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  EXPECT_NE(bad.err.find("detections.json"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(tmp / "bad"));
}

}  // namespace cropsight::batch_test
