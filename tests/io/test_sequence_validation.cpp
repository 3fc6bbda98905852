// Every way a sequence can be wrong is an Error whose where() names the offending file.
#include <gtest/gtest.h>
#include <unistd.h>

#include <functional>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/sequence.hpp"
#include "io/sequence_fixture.hpp"
#include "testing/testing.hpp"

namespace cropsight::io {
namespace {

using namespace cropsight::testing;
namespace fs = std::filesystem;

class SequenceValidation : public ::testing::Test {
 protected:
  void SetUp() override { write_fixture_sequence(seq, 3); }
  /// Opening (and reading every frame of) the sequence throws an Error naming `file`.
  void expect_error(const fs::path& file, const std::string& words) {
    try {
      SequenceReader r(seq);
      for (int i = 0; i < r.size(); ++i) r.read(i);
      FAIL() << "no error; expected one naming " << file;
    } catch (const Error& e) {
      EXPECT_EQ(e.where(), file.string()) << e.what();
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "one line: " << e.what();
    }
  }
  void put(const fs::path& rel, const std::string& text) { write_file_atomic(seq / rel, text); }

  TempDir tmp;
  fs::path seq = tmp / "seq";
};

TEST_F(SequenceValidation, ValidSequenceOpens) { EXPECT_NO_THROW(SequenceReader{seq}.read(2)); }

TEST_F(SequenceValidation, MissingDirectory) {
  seq = tmp / "nope";
  expect_error(seq, "not found");
}

TEST_F(SequenceValidation, CameraYamlMissing) {
  fs::remove(seq / "camera.yaml");
  expect_error(seq / "camera.yaml", "not found");
}

TEST_F(SequenceValidation, CameraYamlUnreadable) {
  if (::geteuid() == 0) GTEST_SKIP() << "root can read any file";
  fs::permissions(seq / "camera.yaml", fs::perms::none);
  expect_error(seq / "camera.yaml", "cannot read");
}

TEST_F(SequenceValidation, CameraYamlMalformed) {
  put("camera.yaml", "width: [16,\nheight: 12\n");
  expect_error(seq / "camera.yaml", "malformed YAML");
}

TEST_F(SequenceValidation, CameraYamlNotAMapping) {
  put("camera.yaml", "- 1\n- 2\n");
  expect_error(seq / "camera.yaml", "mapping");
}

// fuzz_camera_yaml's first finding: a key that is a mapping or a list escaped as
// YAML::TypedBadConversion (exit 1, "internal error"); fuzz/regressions/camera_yaml/ keeps it.
TEST_F(SequenceValidation, CameraYamlKeyThatIsAMappingOrAList) {
  put("camera.yaml", "{{}}");
  expect_error(seq / "camera.yaml", "line 1: a key must be a plain name, not a mapping");
  put("camera.yaml", "width: 16\n[a, b]: 1\n");
  expect_error(seq / "camera.yaml", "line 2: a key must be a plain name, not a list");
}

TEST_F(SequenceValidation, CameraYamlMissingKey) {
  put("camera.yaml", "width: 16\nheight: 12\nfx: 10\ncx: 7.5\ncy: 5.5\ndepth_scale: 0.001\n");
  expect_error(seq / "camera.yaml", "'fy'");
}

TEST_F(SequenceValidation, CameraYamlBadValues) {
  put("camera.yaml", "width: 16\nheight: 12\nfx: abc\nfy: 10\ncx: 7.5\ncy: 5.5\ndepth_scale: 0.001\n");
  expect_error(seq / "camera.yaml", "'fx'");
  put("camera.yaml", "width: 16\nheight: 12\nfx: -3\nfy: 10\ncx: 7.5\ncy: 5.5\ndepth_scale: 0.001\n");
  expect_error(seq / "camera.yaml", "focal");
  put("camera.yaml", "width: 16.5\nheight: 12\nfx: 3\nfy: 10\ncx: 7.5\ncy: 5.5\ndepth_scale: 0.001\n");
  expect_error(seq / "camera.yaml", "'width'");
  put("camera.yaml", "width: 16\nheight: 12\nfx: 3\nfy: 10\ncx: 7.5\ncy: 5.5\ndepth_scale: 0\n");
  expect_error(seq / "camera.yaml", "depth_scale");
  put("camera.yaml", "width: 16\nheight: 12\nfx: 3\nfy: 10\ncx: 7.5\ncy: 5.5\ndepth_scale: 0.001\nfocal: 3\n");
  expect_error(seq / "camera.yaml", "unknown key 'focal'");
}

TEST_F(SequenceValidation, CameraSizeDiffersFromImages) {
  put("camera.yaml", "width: 20\nheight: 12\nfx: 10\nfy: 10\ncx: 7.5\ncy: 5.5\ndepth_scale: 0.001\n");
  expect_error(seq / "depth" / "000000.png", "camera.yaml says 20x12");
}

TEST_F(SequenceValidation, NoDepthDirectory) {
  fs::remove_all(seq / "depth");
  expect_error(seq / "depth", "directory not found");
}

TEST_F(SequenceValidation, NoFrames) {
  fs::remove_all(seq / "depth");
  fs::create_directory(seq / "depth");
  expect_error(seq / "depth", "no frames");
}

TEST_F(SequenceValidation, GapInDepthFrames) {
  fs::remove(seq / "depth" / "000001.png");
  expect_error(seq / "depth" / "000001.png", "missing frame");
}

TEST_F(SequenceValidation, FramesNotStartingAtZero) {
  fs::remove(seq / "depth" / "000000.png");
  expect_error(seq / "depth" / "000000.png", "missing frame");
}

TEST_F(SequenceValidation, LastDepthFrameMissingMeansExtraColourFrame) {
  fs::remove(seq / "depth" / "000002.png");
  expect_error(seq / "color" / "000002.png", "extra frame");
}

TEST_F(SequenceValidation, MissingColourFrame) {
  fs::remove(seq / "color" / "000001.png");
  expect_error(seq / "color" / "000001.png", "missing frame");
}

TEST_F(SequenceValidation, MissingLabelFrame) {
  fs::remove(seq / "labels" / "000000.png");
  expect_error(seq / "labels" / "000000.png", "missing frame");
}

TEST_F(SequenceValidation, LabelsWithoutDepth) {
  fs::copy_file(seq / "labels" / "000000.png", seq / "labels" / "000003.png");
  expect_error(seq / "labels" / "000003.png", "labels without depth");
}

TEST_F(SequenceValidation, UnexpectedFileInFrameDirectory) {
  put("depth/notes.txt", "x");
  expect_error(seq / "depth" / "notes.txt", "unexpected entry");
  fs::remove(seq / "depth" / "notes.txt");
  fs::copy_file(seq / "depth" / "000000.png", seq / "depth" / "0001.png");
  expect_error(seq / "depth" / "0001.png", "NNNNNN.png");
}

TEST_F(SequenceValidation, UnexpectedTopLevelEntry) {
  put("groundtruth.jsn", "{}");
  expect_error(seq / "groundtruth.jsn", "unexpected entry");
}

TEST_F(SequenceValidation, EightBitDepth) {
  write_gray(seq / "depth" / "000001.png", GrayImage(16, 12, 100));
  expect_error(seq / "depth" / "000001.png", "8-bit");
}

TEST_F(SequenceValidation, WrongDepthSize) {
  write_u16(seq / "depth" / "000002.png", Image<std::uint16_t>(8, 12, 1000));
  expect_error(seq / "depth" / "000002.png", "image is 8x12");
}

TEST_F(SequenceValidation, ColourLabelImage) {
  write_color(seq / "labels" / "000001.png", ColorImage(16, 12));
  expect_error(seq / "labels" / "000001.png", "3-channel");
}

TEST_F(SequenceValidation, SixteenBitColour) {
  write_u16(seq / "color" / "000000.png", Image<std::uint16_t>(16, 12, 5));
  expect_error(seq / "color" / "000000.png", "16-bit");
}

TEST_F(SequenceValidation, WrongColourSize) {
  write_color(seq / "color" / "000002.png", ColorImage(16, 10));
  expect_error(seq / "color" / "000002.png", "image is 16x10");
}

TEST_F(SequenceValidation, CorruptPng) {
  put("depth/000001.png", "garbage");
  expect_error(seq / "depth" / "000001.png", "decode");
}

TEST_F(SequenceValidation, PosesMalformed) {
  const fs::path p = seq / "poses.csv";
  put("poses.csv", "frame,time,x,y,z\n0,0,0,0,0\n");
  expect_error(p, "header");
  put("poses.csv", "frame,timestamp,x,y,z\n0,0,0,0\n1,0,0,0,0\n2,0,0,0,0\n");
  expect_error(p, "line 2: expected 5");
  put("poses.csv", "frame,timestamp,x,y,z\n0,0,0,0,0\n1,0,abc,0,0\n2,0,0,0,0\n");
  expect_error(p, "line 3: expected a finite number, got 'abc'");
  put("poses.csv", "frame,timestamp,x,y,z\n0,0,0,0,0\n2,0,0,0,0\n1,0,0,0,0\n");
  expect_error(p, "expected frame 1");
  put("poses.csv", "frame,timestamp,x,y,z\n0,0,0,0,0\n1,0,0,0,0\n");
  expect_error(p, "has 2 rows but the sequence has 3");
  put("poses.csv", "");
  expect_error(p, "empty");
  put("poses.csv", "frame,timestamp,x,y,z\n0,-1,0,0,0\n1,0,0,0,0\n2,0,0,0,0\n");
  expect_error(p, "line 2: timestamp must be >= 0");
  put("poses.csv", "frame,timestamp,x,y,z\n0,0,0,0,0\n1,0.2,0,0,0\n2,0.1,0,0,0\n");
  expect_error(p, "line 4: timestamp 0.1 goes back in time");
}

TEST_F(SequenceValidation, CameraYamlDuplicateKeyAndAbsurdPrincipalPoint) {
  // yaml-cpp keeps both entries and a lookup takes the first, so a second fx was silently ignored.
  put("camera.yaml", "width: 16\nheight: 12\nfx: 10\nfy: 10\ncx: 7.5\ncy: 5.5\ndepth_scale: 0.001\nfx: 300\n");
  expect_error(seq / "camera.yaml", "duplicate key 'fx'");
  put("camera.yaml", "width: 16\nheight: 12\nfx: 10\nfy: 10\ncx: 1e308\ncy: 5.5\ndepth_scale: 0.001\n");
  expect_error(seq / "camera.yaml", "principal point");
}

TEST_F(SequenceValidation, GroundTruthNumberOutOfRange) {
  // nlohmann reports 1e999 as out_of_range, not parse_error: still one line naming the file.
  put("groundtruth.json", R"({"instances": [{"id": 1, "position": [0,0,0], "diameter_mm": 1e999}]})");
  expect_error(seq / "groundtruth.json", "number overflow");
}

TEST_F(SequenceValidation, GroundTruthMalformed) {
  const fs::path g = seq / "groundtruth.json";
  put("groundtruth.json", "{\"instances\": [");
  expect_error(g, "malformed JSON");
  put("groundtruth.json", "[]");
  expect_error(g, "object");
  put("groundtruth.json", "{\"attributes\": {}}");
  expect_error(g, "\"instances\" must be an array");
  put("groundtruth.json", R"({"instances": [{"id": 1.5, "position": [0,0,0], "diameter_mm": 1}]})");
  expect_error(g, "\"id\" must be an integer");
  put("groundtruth.json", R"({"instances": [{"id": 0, "position": [0,0,0], "diameter_mm": 1}]})");
  expect_error(g, "1..65535");
  put("groundtruth.json", R"({"instances": [{"id": 1, "position": [0,0], "diameter_mm": 1}]})");
  expect_error(g, "\"position\"");
  put("groundtruth.json", R"({"instances": [{"id": 1, "position": [0,0,0]}]})");
  expect_error(g, "\"diameter_mm\"");
  put("groundtruth.json",
      R"({"instances": [{"id": 1, "position": [0,0,0], "diameter_mm": 1}, {"id": 1, "position": [0,0,0], "diameter_mm": 2}]})");
  expect_error(g, "duplicate id 1");
  put("groundtruth.json", R"({"instances": [{"id": 1, "position": [0,0,0], "diameter_mm": 1, "note": "x"}]})");
  expect_error(g, "\"note\" must be a number");
  put("groundtruth.json", R"({"instances": [], "extra": 1})");
  expect_error(g, "unknown key \"extra\"");
}

TEST_F(SequenceValidation, ReadOutOfRange) {
  SequenceReader r(seq);
  EXPECT_THROW(r.read(3), Error);
  EXPECT_THROW(r.read(-1), Error);
}

}  // namespace
}  // namespace cropsight::io
