// cropsight batch (local engine) and cropsight merge, end to end on four simulated passes.
#include <sys/wait.h>
#include <unistd.h>

#include "batch_fixture.hpp"

namespace cropsight::batch_test {

class BatchCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    tmp_ = new cropsight::testing::TempDir();
    error_ = shared_passes(passes_);
  }
  static void TearDownTestSuite() { delete tmp_; }
  void SetUp() override {
    if (!error_.empty()) GTEST_FAIL() << "simulation failed: " << error_;
  }
  static fs::path dir() { return tmp_->path(); }
  static std::vector<fs::path> passes(int n = 4) { return pass_paths(passes_, n); }
  static cropsight::testing::TempDir* tmp_;
  static fs::path passes_;
  static std::string error_;
};
cropsight::testing::TempDir* BatchCli::tmp_ = nullptr;
fs::path BatchCli::passes_;
std::string BatchCli::error_;

TEST_F(BatchCli, LocalBatchMergesGeoReferencesAndResumes) {
  const fs::path m = write_manifest(dir() / "m.yaml", passes()), out = dir() / "local";
  const auto r = run_cli("batch --manifest " + shell_quoted(m) + " --out " + shell_quoted(out) + " --workers 2 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(json_number(r.out, "ran"), 4);
  const std::string map = slurp(out / "field-map.csv");
  ASSERT_NE(map.find("latitude_deg,longitude_deg"), std::string::npos) << map;
  EXPECT_TRUE(fs::exists(out / "field-map.geojson"));
  EXPECT_NE(slurp(out / "passes.csv").find("pass4,1,16,"), std::string::npos) << slurp(out / "passes.csv");
  // Overlapping passes saw some heads twice: fewer merged heads than heads in the pass maps.
  EXPECT_LT(json_number(r.out, "heads"), json_number(r.out, "heads_in"));
  EXPECT_GT(json_number(r.out, "heads"), 0);
  // The HTML summary: one map circle per merged head among its marks, the shards' run times.
  const std::string html = slurp(out / "report.html");
  long marks = 0;
  for (auto at = html.find("class=\"cs-mark\""); at != std::string::npos; at = html.find("class=\"cs-mark\"", at + 1))
    ++marks;
  EXPECT_GT(marks, json_number(r.out, "heads")) << html.substr(0, 400);
  EXPECT_NE(html.find("run time per shard"), std::string::npos);

  const auto again = run_cli("batch --manifest " + shell_quoted(m) + " --out " + shell_quoted(out) + " --json");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(json_number(again.out, "already_done"), 4);
  EXPECT_EQ(json_number(again.out, "ran"), 0);
  EXPECT_EQ(slurp(out / "field-map.csv"), map);  // same shards, same bytes

  // The GeoJSON as a real consumer reads it: GDAL's ogrinfo (what QGIS uses underneath).
  if (std::system("command -v ogrinfo >/dev/null 2>&1") != 0) GTEST_SKIP() << "ogrinfo (gdal-bin) not installed";
  const fs::path info = dir() / "ogrinfo.txt";
  ASSERT_EQ(std::system(
                ("ogrinfo -ro -al -so " + shell_quoted(out / "field-map.geojson") + " >" + shell_quoted(info) + " 2>&1")
                    .c_str()),
            0)
      << slurp(info);
  const std::string text = slurp(info);
  EXPECT_NE(text.find("Geometry: 3D Point"), std::string::npos) << text;
  EXPECT_NE(text.find("Feature Count: " + std::to_string(json_number(r.out, "heads"))), std::string::npos) << text;
  EXPECT_NE(text.find("diameter_mm: Real"), std::string::npos) << text;
  EXPECT_NE(text.find("WGS 84"), std::string::npos) << text;
  // Extent: longitude ~0.12 and latitude ~52.2, within a few metres of the origin.
  EXPECT_NE(text.find("Extent: (0.1199"), std::string::npos) << text;
}

TEST_F(BatchCli, InterruptedBatchRunsOnlyTheRest) {
  const fs::path m = write_manifest(dir() / "m-kill.yaml", passes()), out = dir() / "killed";
  const pid_t pid = start_cli("batch --manifest " + shell_quoted(m) + " --out " + shell_quoted(out) + " --workers 1",
                              dir() / "killed.log");
  ASSERT_TRUE(wait_for([&] { return done_shards(out) >= 2; }, 120)) << slurp(dir() / "killed.log");
  kill(-pid, SIGKILL);  // mid-shard: the third one is running
  waitpid(pid, nullptr, 0);
  const int done = done_shards(out);
  EXPECT_EQ(incomplete_visible_shards(out), 0);  // a killed shard leaves nothing that looks done
  EXPECT_FALSE(fs::exists(out / "field-map.csv"));
  const auto r = run_cli("batch --manifest " + shell_quoted(m) + " --out " + shell_quoted(out) + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(json_number(r.out, "already_done"), done);
  EXPECT_EQ(json_number(r.out, "ran"), 4 - done);
  EXPECT_LT(done, 4) << "the kill came too late to test anything";
}

TEST_F(BatchCli, FrameRangeShardsKeepEachHeadOnce) {
  // The seam rule (batch/plan.hpp): ranges of 6 frames with 10 frames of overlap find the heads
  // the whole recordings find, each once (no head kept by two shards, none lost at a cut).
  const fs::path whole = write_manifest(dir() / "m-whole.yaml", passes()),
                 ranges = write_manifest(dir() / "m-ranges.yaml", passes(),
                                         "shards: {frames_per_shard: 6, overlap_frames: 10}\n");
  const auto a =
      run_cli("batch --json --workers 2 --manifest " + shell_quoted(whole) + " --out " + shell_quoted(dir() / "whole"));
  const auto b = run_cli("batch --json --workers 2 --manifest " + shell_quoted(ranges) + " --out " +
                         shell_quoted(dir() / "ranges"));
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_EQ(json_number(b.out, "maps"), 12);  // 3 ranges per 16-frame pass
  EXPECT_EQ(json_number(b.out, "heads"), json_number(a.out, "heads")) << a.out << "\n" << b.out;
  EXPECT_EQ(json_number(b.out, "harvestable"), json_number(a.out, "harvestable"));
}

TEST_F(BatchCli, AnotherPlanIsRefusedUnlessForcedAndAUsersFileAlways) {
  const fs::path one = dir() / "one.yaml", two = dir() / "two.yaml", out = dir() / "forced";
  write_manifest(one, passes(1));
  write_manifest(two, passes(2));
  const std::string to = " --out " + shell_quoted(out);
  ASSERT_EQ(run_cli("batch --quiet --manifest " + shell_quoted(one) + to).exit_code, 0);
  const auto other = run_cli("batch --quiet --manifest " + shell_quoted(two) + to);
  EXPECT_EQ(other.exit_code, 2);
  EXPECT_NE(other.err.find("another plan"), std::string::npos) << other.err;
  const auto forced = run_cli("batch --json --force --manifest " + shell_quoted(two) + to);
  ASSERT_EQ(forced.exit_code, 0) << forced.err;
  EXPECT_EQ(json_number(forced.out, "ran"), 2);  // started over
  cropsight::testing::write_text(out / "my-notes.txt", "rows 3-4 flooded");
  EXPECT_EQ(run_cli("batch --quiet --force --manifest " + shell_quoted(one) + to).exit_code, 2);
  EXPECT_EQ(slurp(out / "my-notes.txt"), "rows 3-4 flooded");
}

TEST_F(BatchCli, FailedShardExits3AndTheRerunFinishesIt) {
  fs::create_directories(dir() / "broken");
  fs::copy(passes_ / "pass2", dir() / "broken" / "pass2", fs::copy_options::recursive);
  const fs::path frame = dir() / "broken" / "pass2" / "depth" / "000005.png", out = dir() / "partial";
  const std::string good = slurp(frame);
  cropsight::testing::write_text(frame, "not a PNG");
  const fs::path m = write_manifest(dir() / "m-broken.yaml", {passes_ / "pass1", dir() / "broken" / "pass2"});
  const auto r = run_cli("batch --manifest " + shell_quoted(m) + " --out " + shell_quoted(out) + " --workers 2");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.out.find("shard pass2:"), std::string::npos) << r.out;  // the summary names it and why
  EXPECT_NE(r.out.find("000005.png"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(out / "shards" / "pass2"));
  EXPECT_FALSE(fs::exists(out / "field-map.csv"));
  std::ofstream(frame, std::ios::binary) << good;
  const auto again = run_cli("batch --json --manifest " + shell_quoted(m) + " --out " + shell_quoted(out));
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(json_number(again.out, "already_done"), 1);
  EXPECT_EQ(json_number(again.out, "ran"), 1);
}

TEST_F(BatchCli, BadManifestIsOneLineAndExit2) {
  const std::string p1 = "'" + (passes_ / "pass1").string() + "'",
                    p1again = "'" + (passes_ / "." / "pass1").string() + "'";
  const std::string cases[] = {
      "recordings: [" + p1 + ", nowhere]\npipeline: {crop: broccoli}\n",                   // missing recording
      "recordings: [" + p1 + "]\npipeline: {crop: broccoli, config: no-such-preset}\n",    // unknown preset
      "recordings: [" + p1 + ", " + p1again + "]\npipeline: {crop: broccoli}\n",           // duplicate output
      "recordings: [" + p1 + "]\npipeline: {crop: broccoli, sets: {tracking.nope: 1}}\n",  // unknown key
      "recordings: [" + p1 + "]\npipeline: {crop: broccoli}\nslurm: {partiton: x}\n",      // misspelt option
      "recordings: [" + p1 + "]\npipeline: {crop: cabbage}\n",
  };
  for (const std::string& text : cases) {
    cropsight::testing::write_text(dir() / "bad.yaml", text);
    const fs::path out = dir() / "bad-out";
    const auto r = run_cli("batch --manifest " + shell_quoted(dir() / "bad.yaml") + " --out " + shell_quoted(out));
    EXPECT_EQ(r.exit_code, 2) << text;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("bad.yaml"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << text;
  }
}

TEST_F(BatchCli, CsvManifestRunsTheSameBatchAsYaml) {
  const fs::path yaml = write_manifest(dir() / "same.yaml", passes(2), "  model: broccoli-oes-general\n");
  std::string csv = "# recordings listed by a script\nrecording,crop,model\n";
  csv += "\"" + (passes_ / "pass1").string() + "\",broccoli,broccoli-oes-general\n";
  csv += (passes_ / "pass2").string() + ",,\n";  // empty cells: the other rows' values
  cropsight::testing::write_text(dir() / "same.csv", csv);
  const auto a = run_cli("batch --quiet --manifest " + shell_quoted(yaml) + " --out " + shell_quoted(dir() / "y"));
  const auto b =
      run_cli("batch --quiet --manifest " + shell_quoted(dir() / "same.csv") + " --out " + shell_quoted(dir() / "c"));
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_EQ(slurp(dir() / "c" / "field-map.csv"), slurp(dir() / "y" / "field-map.csv"));

  const std::string p1 = (passes_ / "pass1").string(), p2 = (passes_ / "pass2").string();
  const std::string bad[] = {
      "recording,crop\n" + p1 + ",broccoli\n" + p2 + ",potato\n",  // two pipelines
      "recording,crop,colour\n" + p1 + ",broccoli,red\n",          // unknown column
      "path,crop\n" + p1 + ",broccoli\n",                          // no recording column
      "recording,crop\n" + p1 + ",broccoli,extra\n",               // field count
      "recording,crop\n\"" + p1 + ",broccoli\n",                   // unterminated quote
      "recording,crop\n" + p1 + "\n",                              // field count (too few)
      "recording\n" + p1 + "\n",                                   // no crop
      "recording,crop\nnowhere,broccoli\n",                        // missing recording
  };
  for (const std::string& text : bad) {
    cropsight::testing::write_text(dir() / "bad.csv", text);
    const auto r = run_cli("batch --manifest " + shell_quoted(dir() / "bad.csv") + " --out " +
                           shell_quoted(dir() / "bad-csv-out"));
    EXPECT_EQ(r.exit_code, 2) << text;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("bad.csv"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir() / "bad-csv-out")) << text;
  }
}

TEST_F(BatchCli, MergeCommandFusesPassMaps) {
  const fs::path m = write_manifest(dir() / "m.yaml", passes()), out = dir() / "local";
  ASSERT_EQ(run_cli("batch --quiet --manifest " + shell_quoted(m) + " --out " + shell_quoted(out)).exit_code, 0);
  std::string maps, data;
  for (int i = 1; i <= 4; ++i) {
    const std::string p = "pass" + std::to_string(i);
    maps += (i > 1 ? "," : "") + (out / "shards" / p / "field-map.csv").string();
    data += (i > 1 ? "," : "") + (passes_ / p).string();
  }
  const auto r = run_cli("merge --json --maps " + shell_quoted(maps) + " --data " + shell_quoted(data) + " --out " +
                         shell_quoted(dir() / "merged"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The same maps in the same order: the same heads as the batch's merge.
  const std::string batch_map = slurp(out / "field-map.csv"), merged = slurp(dir() / "merged" / "field-map.csv");
  EXPECT_EQ(std::count(batch_map.begin(), batch_map.end(), '\n'), std::count(merged.begin(), merged.end(), '\n'));
  EXPECT_TRUE(fs::exists(dir() / "merged" / "field-map.geojson"));
  const auto again = run_cli("merge --maps " + shell_quoted(maps) + " --out " + shell_quoted(dir() / "merged"));
  EXPECT_EQ(again.exit_code, 2) << "an existing output is replaced only with --force";
}

}  // namespace cropsight::batch_test
