// A simulated pass through a bag whose colour stream dropped frames: import keeps every frame
// that has its colour, skips and counts the others, and keeps depth, colour, times and poses.
#include <gtest/gtest.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/Image.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "cropsight/bridge/sequence_io.hpp"
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

}  // namespace
}  // namespace cropsight::ros_io
