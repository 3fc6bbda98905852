// Sequence folder <-> bag (ros/src/bag_io.cpp): byte-exact depth and colour, the same camera,
// the poses through /tf; bad bags are one Error naming the file and leave no output.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cropsight/bridge/sequence_io.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight_ros/bag_io.hpp"
#include "ros_test_support.hpp"

namespace fs = std::filesystem;

namespace cropsight::ros_io {
namespace {

using ros_test::error_of;

// A 3-frame sequence with depth, colour and poses, every pixel distinct.
fs::path make_sequence(const fs::path& dir, bool poses = true) {
  bridge::CameraModel cam;
  cam.width = 8;
  cam.height = 6;
  cam.fx = 50;
  cam.fy = 51;
  cam.cx = 3.5;
  cam.cy = 2.5;
  cam.distortion = {0.01, -0.02, 0, 0, 0.003};
  bridge::SequenceSink sink(dir.string(), cam);
  for (int i = 0; i < 3; ++i) {
    bridge::FrameBuffers f;
    f.index = i;
    f.timestamp = 0.25 * i;
    f.camera = cam;
    for (int p = 0; p < 48; ++p) {
      f.depth.push_back(std::uint16_t(p == 5 ? 0 : 500 + 97 * p + i));
      for (int c = 0; c < 3; ++c) f.rgb.push_back(std::uint8_t(p * 5 + c * 60 + i));
    }
    if (poses) {
      f.has_camera_position = true;
      f.camera_position[0] = 0.1 * i;
      f.camera_position[1] = -0.01;
      f.camera_position[2] = 1.25;
    }
    sink.write(f);
  }
  sink.finish();
  return dir;
}

TEST(BagIo, RoundTripIsExactForDepthColourCameraAndPoses) {
  const fs::path d = ros_test::scratch_dir("bag_round_trip");
  make_sequence(d / "seq");
  BagExportOptions e;
  e.sequence = (d / "seq").string();
  e.bag = (d / "s.bag").string();
  const BagExportSummary s = export_sequence_bag(e);
  EXPECT_EQ(s.frames, 3);
  EXPECT_EQ(s.messages, 3 * 4);  // depth, camera_info, colour, /tf
  EXPECT_FALSE(fs::exists(e.bag + ".partial"));
  BagImportOptions i;
  i.bag = e.bag;
  i.out = (d / "back").string();
  const BagImportSummary r = import_bag_sequence(i);
  EXPECT_EQ(r.frames, 3);
  EXPECT_TRUE(r.color);
  bridge::SequenceSource a((d / "seq").string()), b((d / "back").string());
  ASSERT_EQ(b.size(), 3);
  EXPECT_EQ(b.camera().fx, a.camera().fx);
  EXPECT_EQ(b.camera().cy, a.camera().cy);
  EXPECT_EQ(b.camera().distortion, a.camera().distortion);
  for (int k = 0; k < 3; ++k) {
    const auto fa = a.read(k), fb = b.read(k);
    EXPECT_EQ(fb.depth, fa.depth) << "frame " << k;
    EXPECT_EQ(fb.rgb, fa.rgb) << "frame " << k;
    ASSERT_TRUE(fb.has_camera_position);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(fb.camera_position[c], fa.camera_position[c]);
    EXPECT_NEAR(fb.timestamp, fa.timestamp, 1e-9);  // ROS time has nanoseconds
  }
  // The PNG files themselves are byte-identical too.
  for (const char* f : {"depth/000001.png", "color/000002.png"}) {
    std::ifstream x(d / "seq" / f, std::ios::binary), y(d / "back" / f, std::ios::binary);
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(x), {}), std::string(std::istreambuf_iterator<char>(y), {}))
        << f;
  }
}

TEST(BagIo, BadBagsAreOneErrorNamingTheFileAndLeaveNoSequence) {
  const fs::path d = ros_test::scratch_dir("bag_bad");
  make_sequence(d / "seq", /*poses=*/false);
  BagExportOptions e;
  e.sequence = (d / "seq").string();
  e.bag = (d / "s.bag").string();
  export_sequence_bag(e);
  // An existing bag is not replaced without overwrite.
  EXPECT_NE(error_of([&] { export_sequence_bag(e); }).find("exists"), std::string::npos);

  BagImportOptions i;
  i.out = (d / "out").string();
  i.bag = (d / "missing.bag").string();
  EXPECT_EQ(error_of([&] { import_bag_sequence(i); }), i.bag + ": no such file");
  // Truncated in the middle.
  const std::string whole = [&] {
    std::ifstream in(e.bag, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }();
  std::ofstream(d / "cut.bag", std::ios::binary) << whole.substr(0, whole.size() / 2);
  i.bag = (d / "cut.bag").string();
  EXPECT_EQ(error_of([&] { import_bag_sequence(i); }).rfind(i.bag + ": ", 0), 0u);
  std::ofstream(d / "text.bag") << "not a bag\n";
  i.bag = (d / "text.bag").string();
  EXPECT_NE(error_of([&] { import_bag_sequence(i); }).find(i.bag + ": not a readable ROS bag"), std::string::npos);
  // A topic that is not there.
  i.bag = e.bag;
  i.topics.depth = "/kinect2/sd/image_depth_rect";
  EXPECT_NE(error_of([&] { import_bag_sequence(i); }).find("has no message on the depth topic /kinect2"),
            std::string::npos);
  EXPECT_FALSE(fs::exists(i.out));
  // A depth scale that 16UC1 cannot carry.
  fs::create_directories(d / "scaled");
  bridge::CameraModel cam;
  cam.width = cam.height = 2;
  cam.fx = cam.fy = 10;
  cam.depth_scale = 0.000125;
  {
    bridge::SequenceSink sink((d / "scaled/seq").string(), cam);
    bridge::FrameBuffers f;
    f.camera = cam;
    f.depth = {1, 2, 3, 4};
    sink.write(f);
    sink.finish();
  }
  e.sequence = (d / "scaled/seq").string();
  e.bag = (d / "scaled.bag").string();
  EXPECT_NE(error_of([&] { export_sequence_bag(e); }).find("depth_scale"), std::string::npos);
  EXPECT_FALSE(fs::exists(e.bag));
}

// Found by fuzz_bag (fuzz/regressions/bag/): a connection record's header length of 4 GB that
// rosbag allocated, and a CameraInfo whose D length (14 GB) roscpp's deserialiser allocated.
// The record walk (bag_check.cpp) and the message check refuse both, naming the file; a record
// length past the end of a valid bag is caught the same way.
TEST(BagIo, DamagedLengthsAreErrorsNotAllocations) {
  const fs::path d = ros_test::scratch_dir("bag_lengths");
  BagImportOptions i;
  i.out = (d / "out").string();
  for (const char* name : {"oom-12d08eb90082", "oom-2c461aaa3cac", "crash-4177f5308a73"}) {
    i.bag = std::string(CROPSIGHT_SOURCE_DIR) + "/fuzz/regressions/bag/" + name;
    const std::string e = error_of([&] { import_bag_sequence(i); });
    EXPECT_EQ(e.rfind(i.bag + ": damaged", 0), 0u) << e;
  }
  make_sequence(d / "seq", /*poses=*/false);
  BagExportOptions x;
  x.sequence = (d / "seq").string();
  x.bag = (d / "s.bag").string();
  export_sequence_bag(x);
  std::string bytes = [&] {
    std::ifstream in(x.bag, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }();
  bytes[13] = bytes[14] = bytes[15] = '\xff';  // the bag header record's header length
  std::ofstream(d / "long.bag", std::ios::binary) << bytes;
  i.bag = (d / "long.bag").string();
  EXPECT_NE(error_of([&] { import_bag_sequence(i); }).find("runs past the end of the file"), std::string::npos);
  EXPECT_FALSE(fs::exists(i.out));
}

// `detect broccoli --bag` unpacks the bag to a temporary sequence and gives what `--data` gives on
// the sequence the bag was made from. The unpacked folder goes at the end, and the one a run killed
// by a signal left (.cropsight-bag.tmp-PID-N of a dead PID) goes at the next run (kill safety);
// a live run's is left alone.
TEST(BagIo, DetectOnABagEqualsDetectOnItsSequenceAndCleansWhatKilledRunsLeft) {
  using ros_test::run;
  const fs::path d = ros_test::scratch_dir("bag_detect");
  const std::string model = std::string(CROPSIGHT_SOURCE_DIR) + "/models/broccoli-oes-uk.json";
  ASSERT_EQ(run(ros_test::cli() + " simulate broccoli --frames 3 --seed 5 --out " + (d / "seq").string() +
                " >/dev/null 2>&1"),
            0);
  ASSERT_EQ(run(ros_test::cli() + " export --data " + (d / "seq").string() + " --out " + (d / "s.bag").string() +
                " >/dev/null"),
            0);
  const fs::path tmp = d / "tmp", stale = tmp / ".cropsight-bag.tmp-999999999-1", live = tmp / ".cropsight-bag.tmp-1-1";
  fs::create_directories(stale / "sequence");
  fs::create_directories(live);
  std::ofstream(stale / "sequence" / "000000.png") << "partial";
  ASSERT_EQ(run("TMPDIR=" + tmp.string() + " " + ros_test::cli() + " detect broccoli --data " + (d / "s.bag").string() +
                " --model " + model + " --out " + (d / "bag.jsonl").string() + " --quiet"),
            0);
  ASSERT_EQ(run(ros_test::cli() + " detect broccoli --data " + (d / "seq").string() + " --model " + model + " --out " +
                (d / "seq.jsonl").string() + " --quiet"),
            0);
  // The same detections frame by frame; the timestamps equal to the bag's nanoseconds.
  auto read = [](const fs::path& p) {
    std::ifstream in(p);
    std::vector<nlohmann::json> lines;
    for (std::string line; std::getline(in, line);) lines.push_back(nlohmann::json::parse(line));
    return lines;
  };
  const auto from_bag = read(d / "bag.jsonl"), from_seq = read(d / "seq.jsonl");
  ASSERT_EQ(from_bag.size(), 3u);
  ASSERT_EQ(from_seq.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_FALSE(from_seq[i]["detections"].empty());
    EXPECT_EQ(from_bag[i]["detections"], from_seq[i]["detections"]) << "frame " << i;
    EXPECT_EQ(from_bag[i]["frame"], from_seq[i]["frame"]);
    EXPECT_NEAR(from_bag[i]["timestamp"].get<double>(), from_seq[i]["timestamp"].get<double>(), 1e-9);
  }
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(live));  // process 1 (init) is alive: not ours to remove
  fs::remove(live);
  EXPECT_TRUE(fs::is_empty(tmp));
}

}  // namespace
}  // namespace cropsight::ros_io
