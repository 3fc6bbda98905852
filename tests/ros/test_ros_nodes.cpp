// The nodes against a real roscore (the CTest fixture ros_master, scripts/ros-master.sh): a bag
// made from a simulated sequence is played into each node, frame by frame, and what the node
// publishes must equal what the CLI writes for the same frames; malformed messages are skipped,
// counted on `diagnostics`, and the node stays alive.
#include <cropsight_msgs/HarvestTarget.h>
#include <diagnostic_msgs/DiagnosticArray.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <vision_msgs/Detection2DArray.h>
#include <vision_msgs/Detection3DArray.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>

#include "cropsight/bridge/seedling_runner.hpp"
#include "ros_conversions.hpp"
#include "ros_test_support.hpp"

namespace fs = std::filesystem;
using namespace cropsight::ros_test;

namespace {

const std::string kBin = CROPSIGHT_BIN_DIR;
const std::string kSource = CROPSIGHT_SOURCE_DIR;

// Spins until `done` or `timeout_s`.
bool spin_until(const std::function<bool()>& done, double timeout_s) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout_s);
  while (ros::ok() && ros::WallTime::now() < end) {
    ros::spinOnce();
    if (done()) return true;
    ros::WallDuration(0.002).sleep();
  }
  return done();
}

std::vector<nlohmann::json> read_lines(const fs::path& p) {
  std::vector<nlohmann::json> out;
  std::ifstream in(p);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) out.push_back(nlohmann::json::parse(line));
  return out;
}

// One frame of a bag: its messages by topic.
struct BagFrame {
  ros::Time stamp;
  sensor_msgs::ImageConstPtr depth, color;
  sensor_msgs::CameraInfoConstPtr info;
};

std::vector<BagFrame> read_bag(const fs::path& bag_path) {
  rosbag::Bag bag(bag_path.string(), rosbag::bagmode::Read);
  std::map<ros::Time, BagFrame> frames;
  for (const rosbag::MessageInstance& m : rosbag::View(bag)) {
    BagFrame& f = frames[m.getTime()];
    f.stamp = m.getTime();
    if (m.getTopic() == "/camera/depth/image_raw") f.depth = m.instantiate<sensor_msgs::Image>();
    if (m.getTopic() == "/camera/color/image_raw") f.color = m.instantiate<sensor_msgs::Image>();
    if (m.getTopic() == "/camera/depth/camera_info") f.info = m.instantiate<sensor_msgs::CameraInfo>();
  }
  std::vector<BagFrame> out;
  for (auto& [t, f] : frames) out.push_back(f);
  return out;
}

// Publishers of a node's inputs in namespace `ns`, and a wait until the node subscribed to them.
struct Inputs {
  ros::Publisher depth, info, color;
  Inputs(ros::NodeHandle& nh, const std::string& ns, bool with_color) {
    depth = nh.advertise<sensor_msgs::Image>(ns + "/depth/image_raw", 50);
    info = nh.advertise<sensor_msgs::CameraInfo>(ns + "/depth/camera_info", 50);
    if (with_color) color = nh.advertise<sensor_msgs::Image>(ns + "/color/image_raw", 50);
  }
  bool connected() const {
    return depth.getNumSubscribers() > 0 && info.getNumSubscribers() > 0 && (!color || color.getNumSubscribers() > 0);
  }
  void publish(const BagFrame& f) {
    if (color && f.color) color.publish(f.color);
    depth.publish(f.depth);
    info.publish(f.info);
  }
};

class RosNodes : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ASSERT_TRUE(ros::master::check()) << "no ROS master: run through ctest (fixture ros_master)";
  }
};

TEST_F(RosNodes, BroccoliNodeDetectionsEqualTheCli) {
  const fs::path d = scratch_dir("broccoli_node");
  const std::string model = kSource + "/models/broccoli-oes-uk.json";
  ASSERT_EQ(run(cli() + " simulate broccoli --frames 8 --seed 4242 --out " + (d / "seq").string() + " >/dev/null 2>&1"),
            0);
  ASSERT_EQ(run(cli() + " export " + (d / "seq").string() + " --bag " + (d / "s.bag").string() + " >/dev/null"), 0);
  ASSERT_EQ(run(cli() + " detect broccoli --data " + (d / "seq").string() + " --model " + model + " --out " +
                (d / "cli.jsonl").string() + " --quiet >/dev/null"),
            0);
  const auto expected = read_lines(d / "cli.jsonl");
  const auto frames = read_bag(d / "s.bag");
  ASSERT_EQ(frames.size(), expected.size());

  NodeProcess node(kBin + "/cropsight_broccoli_node",
                   {"__ns:=/b1", "__name:=broccoli", "_model:=" + model, "_map_file:=" + (d / "map.csv").string()},
                   (d / "node.log").string());
  ros::NodeHandle nh;
  std::map<double, vision_msgs::Detection3DArray> got;
  ros::Subscriber sub = nh.subscribe<vision_msgs::Detection3DArray>(
      "/b1/heads", 50, [&](const vision_msgs::Detection3DArray::ConstPtr& m) { got[m->header.stamp.toSec()] = *m; });
  Inputs in(nh, "/b1", false);
  ASSERT_TRUE(spin_until([&] { return in.connected(); }, 30)) << "the node did not subscribe (lazy inputs?)";
  for (const BagFrame& f : frames) {
    in.publish(f);
    ASSERT_TRUE(spin_until([&] { return got.count(f.stamp.toSec()) > 0; }, 30)) << "no heads for " << f.stamp;
  }
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const auto& msg = got[frames[k].stamp.toSec()];
    const auto& cli_dets = expected[k]["detections"];
    EXPECT_EQ(msg.header.frame_id, frames[k].depth->header.frame_id) << "headers are copied from the input";
    ASSERT_EQ(msg.detections.size(), cli_dets.size()) << "frame " << k;
    for (std::size_t j = 0; j < msg.detections.size(); ++j) {
      const auto& r = msg.detections[j].results.at(0);
      EXPECT_NEAR(r.score, cli_dets[j]["score"].get<double>(), 1e-6);
      EXPECT_NEAR(r.pose.pose.position.x, cli_dets[j]["centroid"][0].get<double>(), 1e-6);
      EXPECT_NEAR(r.pose.pose.position.y, cli_dets[j]["centroid"][1].get<double>(), 1e-6);
      EXPECT_NEAR(r.pose.pose.position.z, cli_dets[j]["centroid"][2].get<double>(), 1e-6);
    }
  }
  EXPECT_EQ(node.stop(), 0);
  EXPECT_TRUE(fs::exists(d / "map.csv")) << "the field map is saved on shutdown";
}

TEST_F(RosNodes, MalformedMessagesAreSkippedCountedAndTheNodeLives) {
  const fs::path d = scratch_dir("broccoli_malformed");
  ASSERT_EQ(run(cli() + " simulate broccoli --frames 2 --seed 4243 --out " + (d / "seq").string() + " >/dev/null 2>&1"),
            0);
  ASSERT_EQ(run(cli() + " export " + (d / "seq").string() + " --bag " + (d / "s.bag").string() + " >/dev/null"), 0);
  const auto frames = read_bag(d / "s.bag");
  NodeProcess node(kBin + "/cropsight_broccoli_node",
                   {"__ns:=/b2", "__name:=broccoli", "_model:=" + kSource + "/models/broccoli-oes-uk.json"},
                   (d / "node.log").string());
  ros::NodeHandle nh;
  int heads = 0;
  long skipped = -1;
  ros::Subscriber sub = nh.subscribe<vision_msgs::Detection3DArray>(
      "/b2/heads", 50, [&](const vision_msgs::Detection3DArray::ConstPtr&) { ++heads; });
  ros::Subscriber diag = nh.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/b2/diagnostics", 10, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
        for (const auto& st : m->status)
          for (const auto& kv : st.values)
            if (kv.key == "skipped") skipped = std::stol(kv.value);
      });
  Inputs in(nh, "/b2", false);
  ASSERT_TRUE(spin_until([&] { return in.connected(); }, 30));
  auto publish_at = [&](sensor_msgs::Image depth, sensor_msgs::CameraInfo info, double t) {
    depth.header.stamp = info.header.stamp = ros::Time(t);
    in.depth.publish(depth);
    in.info.publish(info);
    spin_until([] { return false; }, 0.3);
  };
  const sensor_msgs::Image good_depth = *frames[0].depth;
  const sensor_msgs::CameraInfo good_info = *frames[0].info;
  sensor_msgs::Image bad = good_depth;
  bad.encoding = "bgr8";  // wrong encoding
  publish_at(bad, good_info, 10);
  bad = good_depth;
  bad.width -= 1;  // size mismatch with camera_info
  publish_at(bad, good_info, 11);
  sensor_msgs::CameraInfo bad_info = good_info;
  bad_info.K[0] = 0;  // uncalibrated camera_info
  publish_at(good_depth, bad_info, 12);
  bad = good_depth;
  bad.data.resize(bad.data.size() / 3);  // truncated data
  publish_at(bad, good_info, 13);
  EXPECT_EQ(heads, 0);
  EXPECT_TRUE(node.alive());
  publish_at(good_depth, good_info, 14);
  EXPECT_TRUE(spin_until([&] { return heads == 1; }, 30)) << "a good frame after bad ones is processed";
  EXPECT_TRUE(spin_until([&] { return skipped == 4; }, 5)) << "diagnostics count the skipped messages: " << skipped;
  EXPECT_TRUE(node.alive());
  std::ifstream log(d / "node.log");
  const std::string text((std::istreambuf_iterator<char>(log)), {});
  EXPECT_NE(text.find("/b2/depth/image_raw: depth encoding 'bgr8'"), std::string::npos) << text;
}

TEST_F(RosNodes, PotatoNodeHarvestTargetsEqualTheCliAndTheRateThrottles) {
  const fs::path d = scratch_dir("potato_node");
  ASSERT_EQ(run(cli() + " simulate potato --scene sheet --frames 8 --seed 4244 --out " + (d / "seq").string() +
                " >/dev/null 2>&1"),
            0);
  ASSERT_EQ(run(cli() + " export " + (d / "seq").string() + " --bag " + (d / "p.bag").string() + " >/dev/null"), 0);
  ASSERT_EQ(run(cli() + " harvest potato --data " + (d / "seq").string() + " --out " + (d / "cli.jsonl").string() +
                " --quiet >/dev/null 2>&1"),
            0);
  const auto expected = read_lines(d / "cli.jsonl");
  const auto frames = read_bag(d / "p.bag");
  ASSERT_EQ(frames.size(), expected.size());
  for (const double rate : {0.0, 3.0}) {
    const std::string ns = rate == 0 ? "/p_every" : "/p_3hz";
    NodeProcess node(kBin + "/cropsight_potato_node",
                     {"__ns:=" + ns, "__name:=potato", "_rate:=" + std::to_string(rate)},
                     (d / ("node" + ns.substr(1) + ".log")).string());
    ros::NodeHandle nh;
    std::map<double, cropsight_msgs::HarvestTarget> got;
    int detections = 0;
    ros::Subscriber sub = nh.subscribe<cropsight_msgs::HarvestTarget>(
        ns + "/harvest_target", 50,
        [&](const cropsight_msgs::HarvestTarget::ConstPtr& m) { got[m->header.stamp.toSec()] = *m; });
    ros::Subscriber det = nh.subscribe<vision_msgs::Detection2DArray>(
        ns + "/detections", 50, [&](const vision_msgs::Detection2DArray::ConstPtr&) { ++detections; });
    Inputs in(nh, ns, true);
    ASSERT_TRUE(spin_until([&] { return in.connected(); }, 30));
    for (std::size_t k = 0; k < frames.size(); ++k) {
      in.publish(frames[k]);
      ASSERT_TRUE(spin_until([&] { return detections == int(k) + 1; }, 30)) << "frame " << k;
    }
    spin_until([] { return false; }, 0.3);
    if (rate == 0) {
      ASSERT_EQ(got.size(), frames.size());
      for (std::size_t k = 0; k < frames.size(); ++k) {
        const auto& m = got[frames[k].stamp.toSec()];
        const auto& e = expected[k];
        EXPECT_EQ(bool(m.detection), e["detection"].get<bool>()) << "frame " << k;
        EXPECT_EQ(int(m.target_id), e["target_id"].get<int>()) << "frame " << k;
        EXPECT_NEAR(m.x, e["x"].get<double>(), 1e-6);
        EXPECT_NEAR(m.y, e["y"].get<double>(), 1e-6);
        EXPECT_NEAR(m.z, e["z"].get<double>(), 1e-6);
        EXPECT_NEAR(m.angle, e["angle"].get<double>(), 1e-6);
      }
    } else {
      // Simulated frames are 1/15 s apart: at 3 Hz every fifth frame's target is published.
      std::vector<double> stamps;
      for (const auto& [t, m] : got) stamps.push_back(t);
      ASSERT_EQ(stamps.size(), 2u);
      EXPECT_NEAR(stamps[1] - stamps[0], 5.0 / 15.0, 1e-3);
    }
    EXPECT_EQ(node.stop(), 0);
  }
}

TEST_F(RosNodes, SeedlingNodeEnvelopeEqualsTheCli) {
  const fs::path d = scratch_dir("seedling_node");
  ASSERT_EQ(run(cli() + " simulate seedling --pairs 2 --calib-pairs 0 --seed 4245 --quiet --out " +
                (d / "data").string() + " >/dev/null"),
            0);
  NodeProcess node(kBin + "/cropsight_seedling_node", {"__ns:=/s1", "__name:=seedling"}, (d / "node.log").string());
  ros::NodeHandle nh;
  std::map<double, vision_msgs::Detection3DArray> got;
  ros::Subscriber sub = nh.subscribe<vision_msgs::Detection3DArray>(
      "/s1/seedlings", 10,
      [&](const vision_msgs::Detection3DArray::ConstPtr& m) { got[m->header.stamp.toSec()] = *m; });
  auto left_pub = nh.advertise<sensor_msgs::Image>("/s1/left/image_rect_color", 5);
  auto right_pub = nh.advertise<sensor_msgs::Image>("/s1/right/image_rect_color", 5);
  auto left_info_pub = nh.advertise<sensor_msgs::CameraInfo>("/s1/left/camera_info", 5);
  auto right_info_pub = nh.advertise<sensor_msgs::CameraInfo>("/s1/right/camera_info", 5);
  ASSERT_TRUE(
      spin_until([&] { return right_info_pub.getNumSubscribers() > 0 && left_pub.getNumSubscribers() > 0; }, 30));
  int found = 0;
  for (int k = 0; k < 2; ++k) {
    const fs::path pair = d / "data" / ("pair_00" + std::to_string(k));
    const std::string calib = (d / "data/rig.yaml").string(), l = (pair / "left.png").string(),
                      r = (pair / "right.png").string();
    ASSERT_EQ(run(cli() + " detect seedling --left " + l + " --right " + r + " --calib " + calib + " --out " +
                  (pair / "cli.json").string() + " >/dev/null"),
              0);
    std::ifstream in(pair / "cli.json");
    const nlohmann::json e = nlohmann::json::parse(in);
    // What the node receives: the pair rectified as the CLI rectifies it, and camera_infos whose
    // P matrices carry the rectified geometry (as stereo_image_proc publishes).
    const auto rect = cropsight::bridge::read_rectified_pair(calib, l, r);
    const auto& g = rect.geometry;
    sensor_msgs::CameraInfo li, ri;
    li.width = ri.width = std::uint32_t(g.width);
    li.height = ri.height = std::uint32_t(g.height);
    li.P = {g.f, 0, g.cx, 0, 0, g.f, g.cy, 0, 0, 0, 1, 0};
    ri.P = {g.f, 0, g.cx_right, -g.f * g.baseline, 0, g.f, g.cy, 0, 0, 0, 1, 0};
    sensor_msgs::Image lm = cropsight::ros_io::image_from_rgb(rect.left.rgb, g.width, g.height);
    sensor_msgs::Image rm = cropsight::ros_io::image_from_rgb(rect.right.rgb, g.width, g.height);
    const ros::Time t(20 + k);
    lm.header.stamp = rm.header.stamp = li.header.stamp = ri.header.stamp = t;
    lm.header.frame_id = "left_optical";
    left_pub.publish(lm);
    right_pub.publish(rm);
    left_info_pub.publish(li);
    right_info_pub.publish(ri);
    ASSERT_TRUE(spin_until([&] { return got.count(t.toSec()) > 0; }, 30)) << "pair " << k;
    const auto& msg = got[t.toSec()];
    EXPECT_EQ(msg.header.frame_id, "left_optical");
    ASSERT_EQ(msg.detections.size(), e["found"].get<bool>() ? 1u : 0u) << "pair " << k;
    if (!msg.detections.empty()) {
      ++found;
      EXPECT_NEAR(msg.detections[0].bbox.size.x, e["envelope"]["length_m"].get<double>(), 1e-9);
      EXPECT_NEAR(msg.detections[0].bbox.size.y, e["envelope"]["width_m"].get<double>(), 1e-9);
      EXPECT_NEAR(msg.detections[0].bbox.size.z, e["envelope"]["height_m"].get<double>(), 1e-9);
    }
  }
  EXPECT_GT(found, 0) << "the simulated pairs hold seedlings";
  EXPECT_EQ(node.stop(), 0);
}

}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  const std::string uri = fixture_master_uri();
  if (!uri.empty()) setenv("ROS_MASTER_URI", uri.c_str(), 1);
  setenv("ROS_HOSTNAME", "127.0.0.1", 1);
  setenv("ROS_HOME", (std::string(CROPSIGHT_ROS_TEST_DIR) + "/ros_home").c_str(), 1);
  ros::init(argc, argv, "cropsight_test_ros_nodes",
            ros::init_options::AnonymousName | ros::init_options::NoSigintHandler);
  return RUN_ALL_TESTS();
}
