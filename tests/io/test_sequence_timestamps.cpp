// Frame times kept by a sequence without poses (timestamps.csv), and the entries a reader ignores.
#include <gtest/gtest.h>

#include <fstream>
#include <iostream>
#include <sstream>

#include "cropsight/core/error.hpp"
#include "cropsight/io/sequence.hpp"
#include "io/sequence_fixture.hpp"
#include "testing/testing.hpp"

namespace cropsight::io {
namespace {

using namespace cropsight::testing;
namespace fs = std::filesystem;

TEST(SequenceTimestamps, KeptWithoutPoses) {
  TempDir t;
  write_fixture_sequence(t / "seq", 3, true, false, /*pose=*/false, false);
  ASSERT_TRUE(fs::exists(t / "seq" / "timestamps.csv"));
  EXPECT_FALSE(fs::exists(t / "seq" / "poses.csv"));
  const SequenceReader r(t / "seq");
  EXPECT_TRUE(r.info().has_timestamps);
  EXPECT_EQ(r.timestamps(), (std::vector<double>{0.0, 0.25, 0.5}));
  EXPECT_DOUBLE_EQ(r.read(2).timestamp, 0.5);
  EXPECT_FALSE(r.read(2).camera_position.has_value());
}

TEST(SequenceTimestamps, PosesCarryThemAndNoTimeMeansNoFile) {
  TempDir t;
  write_fixture_sequence(t / "posed", 2);
  EXPECT_FALSE(fs::exists(t / "posed" / "timestamps.csv"));
  EXPECT_EQ(SequenceReader(t / "posed").timestamps(), (std::vector<double>{0.0, 0.25}));
  const CameraIntrinsics cam = fixture_camera();
  SequenceWriter w(t / "untimed", cam);
  for (int i = 0; i < 2; ++i) {
    RgbdFrame f = fixture_frame(i, cam, false, false, false);
    f.timestamp = 0;
    w.write(f);
  }
  w.finish();
  EXPECT_FALSE(fs::exists(t / "untimed" / "timestamps.csv"));
  EXPECT_TRUE(SequenceReader(t / "untimed").timestamps().empty());
}

TEST(SequenceTimestamps, BadFiles) {
  TempDir t;
  write_fixture_sequence(t / "seq", 3, true, false, false, false);
  write_text(t / "seq" / "timestamps.csv", "frame,timestamp\n0,0\n1,0.5\n2,0.25\n");
  const std::string back = error_message([&] { SequenceReader r(t / "seq"); });
  EXPECT_NE(back.find("timestamps.csv: line 4: timestamp 0.25 goes back in time"), std::string::npos) << back;
  write_text(t / "seq" / "timestamps.csv", "frame,timestamp\n0,0\n1,nan\n2,1\n");
  EXPECT_NE(error_message([&] { SequenceReader r(t / "seq"); }).find("expected a finite number, got 'nan'"),
            std::string::npos);
  write_text(t / "seq" / "timestamps.csv", "frame,timestamp\n0,0\n1,0.5\n");
  EXPECT_NE(error_message([&] { SequenceReader r(t / "seq"); }).find("has 2 rows but the sequence has 3"),
            std::string::npos);
  // Beside poses.csv, the two must agree.
  write_fixture_sequence(t / "posed", 2);
  write_text(t / "posed" / "timestamps.csv", "frame,timestamp\n0,0\n1,0.3\n");
  const std::string differ = error_message([&] { SequenceReader r(t / "posed"); });
  EXPECT_NE(differ.find("frame 1 has timestamp 0.3"), std::string::npos) << differ;
}

// A README beside the frames is ignored with one notice line; a misspelt known name still fails.
TEST(SequenceTimestamps, UnknownEntriesIgnoredWithANotice) {
  TempDir t;
  write_fixture_sequence(t / "seq", 2);
  write_text(t / "seq" / "README.txt", "recorded on the north field\n");
  fs::create_directory(t / "seq" / "calibration");
  std::ostringstream captured;
  std::streambuf* old = std::cerr.rdbuf(captured.rdbuf());
  std::vector<fs::path> ignored;
  try {
    ignored = SequenceReader(t / "seq").info().ignored;
  } catch (...) {
    std::cerr.rdbuf(old);
    throw;
  }
  std::cerr.rdbuf(old);
  ASSERT_EQ(ignored.size(), 2u);
  EXPECT_EQ(ignored[1].filename(), "calibration");
  const std::string notice = captured.str();
  EXPECT_EQ(std::count(notice.begin(), notice.end(), '\n'), 1) << notice;
  EXPECT_NE(notice.find("ignored 2 entries that are no part of a sequence (README.txt, calibration)"),
            std::string::npos)
      << notice;
  write_text(t / "seq" / "pose.csv", "frame,timestamp,x,y,z\n");
  const std::string misspelt = error_message([&] { SequenceReader r(t / "seq"); });
  EXPECT_NE(misspelt.find("pose.csv: unexpected entry in sequence: did you mean poses.csv?"), std::string::npos)
      << misspelt;
}

}  // namespace
}  // namespace cropsight::io
