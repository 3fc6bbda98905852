// CLI tests of info / export / render / report on fixture sequences written by the test.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cropsight/io/cloud_io.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/image_io.hpp"
#include "io/sequence_fixture.hpp"
#include "testing/testing.hpp"

namespace cropsight {
namespace {

using namespace cropsight::testing;
namespace fs = std::filesystem;
using cropsight::testing::shell_quoted;

/// Exit code 2, exactly one line on stderr, naming `file`, nothing on stdout.
void expect_bad_input(const CommandResult& r, const fs::path& file) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "more than one line: " << r.err;
  EXPECT_NE(r.err.find(file.string()), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

class CliSequence : public ::testing::Test {
 protected:
  void SetUp() override { write_fixture_sequence(seq, 3); }
  TempDir tmp;
  fs::path seq = tmp / "seq";
};

// A mistyped command is named (CLI11 alone said "A subcommand is required").
TEST(Cli, UnknownCommandsAreNamed) {
  auto r = run_cli("frobnicate");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("unknown command 'frobnicate'"), std::string::npos) << r.err;
  r = run_cli("detect brocoli --data x");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("unknown command 'detect brocoli'"), std::string::npos) << r.err;
  r = run_cli("--version");
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST_F(CliSequence, InfoJson) {
  const CommandResult r = run_cli("info --data " + shell_quoted(seq) + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["frames"], 3);
  EXPECT_EQ(j["width"], 16);
  EXPECT_EQ(j["height"], 12);
  EXPECT_EQ(j["instances"], 2);
  EXPECT_GT(j["valid_depth_fraction"].get<double>(), 0.8);
  EXPECT_LT(j["valid_depth_fraction"].get<double>(), 1.0);
  EXPECT_EQ(j["camera"]["fx"].get<double>(), fixture_camera().fx);
  EXPECT_EQ(r.out.find('\n'), r.out.size() - 1) << "one JSON line";
}

TEST_F(CliSequence, InfoText) {
  const CommandResult r = run_cli("info --data " + shell_quoted(seq));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("frames       3"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("16 x 12"), std::string::npos) << r.out;
}

TEST_F(CliSequence, InfoWithoutCameraYaml) {
  fs::remove(seq / "camera.yaml");
  expect_bad_input(run_cli("info --data " + shell_quoted(seq)), seq / "camera.yaml");
}

TEST_F(CliSequence, InfoWithEightBitDepth) {
  io::write_gray(seq / "depth" / "000001.png", GrayImage(16, 12, 50));
  expect_bad_input(run_cli("info --data " + shell_quoted(seq) + " --json"), seq / "depth" / "000001.png");
}

TEST_F(CliSequence, InfoWithMissingFrame) {
  fs::remove(seq / "depth" / "000001.png");
  expect_bad_input(run_cli("info --data " + shell_quoted(seq)), seq / "depth" / "000001.png");
}

TEST_F(CliSequence, InfoOnMissingDirectory) {
  expect_bad_input(run_cli("info --data " + shell_quoted(tmp / "nope")), tmp / "nope");
}

TEST_F(CliSequence, ExportPcdAndPly) {
  for (const char* name : {"f.pcd", "f.ply"}) {
    const CommandResult r =
        run_cli("export --data " + shell_quoted(seq) + " --frame 2 --out " + shell_quoted(tmp / name));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const OrganizedCloud c = io::read_organized_cloud(tmp / name);
    EXPECT_EQ(c.width, 16);
    EXPECT_EQ(c.height, 12);
    EXPECT_TRUE(c.has_color());
    EXPECT_TRUE(c.has_labels());
    const RgbdFrame f = fixture_frame(2, fixture_camera());
    const OrganizedCloud want = to_organized_cloud(f);
    EXPECT_EQ(c.count_valid(), want.count_valid());
    ASSERT_TRUE(want.valid(21));
    EXPECT_EQ(c.z[21], want.z[21]);
  }
}

TEST_F(CliSequence, ExportBadFrameAndFormat) {
  expect_bad_input(run_cli("export --data " + shell_quoted(seq) + " --frame 7 --out " + shell_quoted(tmp / "x.pcd")),
                   seq);
  expect_bad_input(run_cli("export --data " + shell_quoted(seq) + " --frame 0 --out " + shell_quoted(tmp / "x.xyz")),
                   tmp / "x.xyz");
  EXPECT_FALSE(fs::exists(tmp / "x.pcd"));
}

TEST_F(CliSequence, RenderEveryKind) {
  for (const char* what : {"depth", "color", "labels"}) {
    const fs::path out = tmp / (std::string(what) + ".png");
    const CommandResult r =
        run_cli("render --data " + shell_quoted(seq) + " --frame 1 --what " + what + " --out " + shell_quoted(out));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const ColorImage img = io::read_color(out);
    EXPECT_EQ(img.width, 16);
    EXPECT_EQ(img.height, 12);
  }
  // Default: depth with white outlines around the labelled discs.
  ASSERT_EQ(run_cli("render --data " + shell_quoted(seq) + " --frame 0 --out " + shell_quoted(tmp / "o.png")).exit_code,
            0);
  const ColorImage o = io::read_color(tmp / "o.png");
  int white = 0;
  for (const auto& p : o.data) white += p == Rgb8{255, 255, 255};
  EXPECT_GT(white, 4);
}

TEST_F(CliSequence, RenderErrors) {
  const CommandResult r =
      run_cli("render --data " + shell_quoted(seq) + " --frame 0 --what normals --out " + shell_quoted(tmp / "x.png"));
  EXPECT_EQ(r.exit_code, 2);
  write_fixture_sequence(tmp / "depth-only", 1, false, false, false, false);
  expect_bad_input(run_cli("render --data " + shell_quoted(tmp / "depth-only") + " --frame 0 --what color --out " +
                           shell_quoted(tmp / "x.png")),
                   tmp / "depth-only");
  EXPECT_FALSE(fs::exists(tmp / "x.png"));
}

TEST_F(CliSequence, ReportWritesOnePage) {
  const CommandResult r = run_cli("report --data " + shell_quoted(seq) + " --out " + shell_quoted(tmp / "page.html"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("page.html"), std::string::npos);
  const std::string h = io::read_file(tmp / "page.html");
  EXPECT_NE(h.find("data:image/png;base64,"), std::string::npos);
  fs::remove(seq / "camera.yaml");
  expect_bad_input(run_cli("report --data " + shell_quoted(seq) + " --out " + shell_quoted(tmp / "bad.html")),
                   seq / "camera.yaml");
  EXPECT_FALSE(fs::exists(tmp / "bad.html"));
}

// What `make demo` runs (scripts/demo.sh), smaller: a simulated sequence and the shipped model.
// The page opens with the detections over frames; the sequence's metadata table comes after the
// results (it was the page's first screen before).
TEST(CliReport, WithModelOpensWithTheResult) {
  TempDir tmp;
  const fs::path seq = tmp / "uk", page = tmp / "page.html";
  CommandResult r = run_cli("simulate broccoli --variety uk --frames 4 --seed 7 --out " + shell_quoted(seq));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_cli("report --data " + shell_quoted(seq) + " --model " +
              shell_quoted(source_dir() / "models" / "broccoli-oes-uk.json") + " --frames 2 --json --out " +
              shell_quoted(page));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string h = io::read_file(page);
  const std::size_t result = h.find("<h2>Broccoli heads: detections over frames</h2>");
  ASSERT_NE(result, std::string::npos);
  EXPECT_EQ(h.find("<h2>"), result) << "the first section is not the result";
  for (const char* later : {"<h2>Field map</h2>", "<h2>Size</h2>", "<h2>Timing</h2>"})
    EXPECT_LT(result, h.find(later)) << later;
  const std::size_t data = h.find("<h2>Sequence summary</h2>");
  ASSERT_NE(data, std::string::npos);
  EXPECT_LT(h.find("<h2>Timing</h2>"), data);
  EXPECT_LT(h.find("data:image/png;base64,"), data);  // the detection overlays come first
  EXPECT_GT(h.find("valid depth fraction"), data);    // the metadata table follows the results
}

}  // namespace
}  // namespace cropsight
