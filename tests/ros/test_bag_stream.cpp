// A simulated pass through a bag whose colour stream dropped frames: import keeps every frame
// that has its colour, skips and counts the others, and keeps depth, colour, times and poses.
#include <gtest/gtest.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/Image.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "cropsight/bridge/sequence_io.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight_ros/bag_io.hpp"
#include "ros_test_support.hpp"

namespace fs = std::filesystem;

namespace cropsight::ros_io {
namespace {

// Copies `in` to `out` without the colour images of frames `drop` (by header seq), writing each
// remaining colour image before its depth image (a driver's streams interleave either way).
void drop_colour_frames(const fs::path& in, const fs::path& out, const std::set<std::uint32_t>& drop) {
  rosbag::Bag src(in.string(), rosbag::bagmode::Read), dst(out.string(), rosbag::bagmode::Write);
  const BagTopics topics;
  std::vector<rosbag::MessageInstance> held;  // the depth image waiting for its colour
  for (const rosbag::MessageInstance& m : rosbag::View(src)) {
    if (m.getTopic() == topics.color) {
      auto im = m.instantiate<sensor_msgs::Image>();
      if (!drop.count(im->header.seq)) dst.write(m.getTopic(), m.getTime(), m);
      for (const auto& h : held) dst.write(h.getTopic(), h.getTime(), h);
      held.clear();
    } else if (m.getTopic() == topics.depth) {
      held.push_back(m);
    } else {
      dst.write(m.getTopic(), m.getTime(), m);
    }
  }
  for (const auto& h : held) dst.write(h.getTopic(), h.getTime(), h);
  dst.close();
}

TEST(BagStream, DroppedColourFramesAreSkippedAndCounted) {
  const fs::path d = ros_test::scratch_dir("bag_stream");
  ASSERT_EQ(ros_test::run(ros_test::cli() + " simulate broccoli --frames 6 --out " + (d / "sim").string() +
                          " > /dev/null 2>&1"),
            0);
  ASSERT_EQ(ros_test::run(ros_test::cli() + " export --data " + (d / "sim").string() + " --out " +
                          (d / "full.bag").string() + " > /dev/null"),
            0);
  drop_colour_frames(d / "full.bag", d / "dropped.bag", {1, 4});
  BagImportOptions o;
  o.bag = (d / "dropped.bag").string();
  o.out = (d / "back").string();
  const BagImportSummary s = import_bag_sequence(o);
  EXPECT_EQ(s.frames, 4);
  EXPECT_EQ(s.skipped_without_color, 2);
  EXPECT_EQ(s.unmatched_color, 0);
  EXPECT_TRUE(s.color);
  bridge::SequenceSource sim((d / "sim").string()), back(o.out);
  ASSERT_EQ(back.size(), 4);
  const int kept[4] = {0, 2, 3, 5};
  for (int k = 0; k < 4; ++k) {
    const auto a = sim.read(kept[k]), b = back.read(k);
    EXPECT_EQ(b.depth, a.depth) << "frame " << k;
    EXPECT_EQ(b.rgb, a.rgb) << "frame " << k;
    EXPECT_NEAR(b.timestamp, a.timestamp, 1e-6) << "frame " << k;  // ROS time: nanoseconds
    ASSERT_TRUE(b.has_camera_position);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(b.camera_position[c], a.camera_position[c]);
  }
}

// --poses on a bag: a pose file joined to the header stamps replaces the bag's /tf poses.
TEST(BagStream, PoseFileJoinedToTheStamps) {
  const fs::path d = ros_test::scratch_dir("bag_poses");
  ASSERT_EQ(ros_test::run(ros_test::cli() + " simulate broccoli --frames 3 --out " + (d / "sim").string() +
                          " > /dev/null 2>&1"),
            0);
  BagExportOptions e;
  e.sequence = (d / "sim").string();
  e.bag = (d / "s.bag").string();
  export_sequence_bag(e);
  bridge::SequenceSource sim(e.sequence);
  std::ofstream tum(d / "odometry.tum");
  tum.precision(17);
  for (int i = 0; i < sim.size(); ++i) {  // the bag's stamps are e.start_s + timestamp
    const auto f = sim.read(i);
    tum << e.start_s + f.timestamp << " " << f.camera_position[0] + 10 << " " << f.camera_position[1] << " "
        << f.camera_position[2] << " 0 0 0 1\n";
  }
  tum.close();
  BagImportOptions o;
  o.bag = e.bag;
  o.out = (d / "back").string();
  o.poses = (d / "odometry.tum").string();
  const BagImportSummary s = import_bag_sequence(o);
  EXPECT_EQ(s.poses_format, "tum");
  bridge::SequenceSource back(o.out);
  ASSERT_EQ(back.size(), sim.size());
  for (int i = 0; i < sim.size(); ++i) {
    const auto a = sim.read(i), b = back.read(i);
    ASSERT_TRUE(b.has_camera_position);
    EXPECT_NEAR(b.camera_position[0], a.camera_position[0] + 10, 1e-9) << "frame " << i;
    EXPECT_NEAR(b.camera_position[2], a.camera_position[2], 1e-9) << "frame " << i;
  }
  // A pose file that does not cover the frames: one Error naming it, and no sequence.
  std::ofstream(d / "short.tum") << "1.0 0 0 1 0 0 0 1\n";
  o.out = (d / "none").string();
  o.poses = (d / "short.tum").string();
  const std::string error = ros_test::error_of([&] { import_bag_sequence(o); });
  EXPECT_NE(error.find("short.tum: no pose within 0.05 s of frame 1"), std::string::npos) << error;
  EXPECT_FALSE(fs::exists(d / "none"));
}

}  // namespace
}  // namespace cropsight::ros_io

namespace cropsight::ros_io {
namespace {

// Copies `in` to `out` with every colour image twice the size (each pixel a 2x2 block): a colour
// stream of another resolution than depth, as unaligned drivers publish.
void double_colour_size(const fs::path& in, const fs::path& out) {
  rosbag::Bag src(in.string(), rosbag::bagmode::Read), dst(out.string(), rosbag::bagmode::Write);
  const BagTopics topics;
  for (const rosbag::MessageInstance& m : rosbag::View(src)) {
    if (m.getTopic() != topics.color) {
      dst.write(m.getTopic(), m.getTime(), m);
      continue;
    }
    const auto im = m.instantiate<sensor_msgs::Image>();
    sensor_msgs::Image big = *im;
    big.width = 2 * im->width;
    big.height = 2 * im->height;
    big.step = 3 * big.width;
    big.data.assign(std::size_t(big.step) * big.height, 0);
    for (std::uint32_t v = 0; v < big.height; ++v)
      for (std::uint32_t u = 0; u < big.width; ++u)
        for (int c = 0; c < 3; ++c)
          big.data[std::size_t(v) * big.step + 3 * u + std::size_t(c)] =
              im->data[std::size_t(v / 2) * im->step + 3 * (u / 2) + std::size_t(c)];
    dst.write(m.getTopic(), m.getTime(), big);
  }
  dst.close();
}

// Colour of another size, registered with --color-camera and --extrinsics: a colour camera at the
// depth camera's place with twice its focal length sees each depth pixel in a 2x2 block of the
// same colour, so registration gives back the original colour on every pixel with depth.
TEST(BagStream, ColourOfAnotherSizeIsRegisteredToDepth) {
  const fs::path d = ros_test::scratch_dir("bag_registration");
  ASSERT_EQ(ros_test::run(ros_test::cli() + " simulate broccoli --frames 3 --out " + (d / "sim").string() +
                          " > /dev/null 2>&1"),
            0);
  ASSERT_EQ(ros_test::run(ros_test::cli() + " export --data " + (d / "sim").string() + " --out " +
                          (d / "full.bag").string() + " > /dev/null"),
            0);
  double_colour_size(d / "full.bag", d / "big.bag");
  bridge::SequenceSource sim((d / "sim").string());
  const bridge::CameraModel c = sim.read(0).camera;
  std::ofstream(d / "color.yaml") << "width: " << 2 * c.width << "\nheight: " << 2 * c.height << "\nfx: " << 2 * c.fx
                                  << "\nfy: " << 2 * c.fy << "\ncx: " << 2 * c.cx + 0.5 << "\ncy: " << 2 * c.cy + 0.5
                                  << "\ndepth_scale: " << c.depth_scale << "\n";
  std::ofstream(d / "extrinsics.yaml")
      << "depth_to_color:\n  rotation: [1, 0, 0, 0, 1, 0, 0, 0, 1]\n  translation: [0, 0, 0]\n";
  BagImportOptions o;
  o.bag = (d / "big.bag").string();
  o.out = (d / "unregistered").string();
  EXPECT_THROW(import_bag_sequence(o), Error);  // colour of another size without its camera
  EXPECT_FALSE(fs::exists(o.out));
  o.out = (d / "registered").string();
  o.color_camera = (d / "color.yaml").string();
  o.extrinsics = (d / "extrinsics.yaml").string();
  ASSERT_EQ(import_bag_sequence(o).frames, 3);
  bridge::SequenceSource back(o.out);
  for (int k = 0; k < 3; ++k) {
    const auto a = sim.read(k), b = back.read(k);
    ASSERT_EQ(b.rgb.size(), a.rgb.size());
    long compared = 0, equal = 0;
    for (std::size_t i = 0; i < a.depth.size(); ++i) {
      if (a.depth[i] == 0) continue;
      ++compared;
      equal +=
          b.rgb[3 * i] == a.rgb[3 * i] && b.rgb[3 * i + 1] == a.rgb[3 * i + 1] && b.rgb[3 * i + 2] == a.rgb[3 * i + 2];
    }
    EXPECT_GT(compared, 0);
    EXPECT_EQ(equal, compared) << "frame " << k;
  }
}

}  // namespace
}  // namespace cropsight::ros_io
