// import --timestamps: frame times from a CSV keyed by the numbers in the frame files' names.
#include <gtest/gtest.h>

#include "cropsight/core/error.hpp"
#include "io/frame_times_csv.hpp"
#include "testing/testing.hpp"

namespace cropsight::io {
namespace {

using cropsight::testing::error_message;
using cropsight::testing::TempDir;
using cropsight::testing::write_text;

std::vector<RecordingFile> numbered_frames() {
  return {{"0000_depth.png", "0000", 0}, {"0001_depth.png", "0001", 1}, {"0002_depth.png", "0002", 2}};
}

TEST(FrameTimesCsv, RowsByFrameNumberInAnyOrder) {
  TempDir t;
  write_text(t / "t.csv",
             "# kinect2 saver log\ntimestamp,exposure,frame\n1596203844.5,8,1\n1596203844.0,8,0\n"
             "1596203845.25,8,2\n7.0,8,3\n");
  const auto times = detail::frame_times_from_csv(t / "t.csv", numbered_frames());
  EXPECT_EQ(times, (std::vector<double>{1596203844.0, 1596203844.5, 1596203845.25}));
}

TEST(FrameTimesCsv, BadFiles) {
  TempDir t;
  auto error_of = [&](const std::string& text) {
    write_text(t / "t.csv", text);
    return error_message([&] { detail::frame_times_from_csv(t / "t.csv", numbered_frames()); });
  };
  EXPECT_NE(error_of("frame,time\n0,1\n").find("naming the columns 'frame' and 'timestamp'"), std::string::npos);
  EXPECT_NE(error_of("frame,timestamp\n0,1\n1,nan\n2,3\n").find("line 3: timestamp must be a finite number"),
            std::string::npos);
  EXPECT_NE(error_of("frame,timestamp\n0,1\n2,3\n").find("no row for frame 0001 (0001_depth.png)"), std::string::npos);
  EXPECT_NE(error_of("frame,timestamp\n0,1\n1,3\n2,2\n").find("the time of frame 0002 (2 s) does not increase"),
            std::string::npos);
  EXPECT_NE(error_of("frame,timestamp\n0,1\n0,2\n").find("line 3: frame 0 is listed twice"), std::string::npos);
  EXPECT_NE(error_of("").find("empty file"), std::string::npos);
  EXPECT_NE(error_of("frame,timestamp\n0,1\n").find("t.csv"), std::string::npos);
}

}  // namespace
}  // namespace cropsight::io
