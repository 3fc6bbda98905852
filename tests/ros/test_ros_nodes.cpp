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

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>

#include <cropsight_msgs/GrapeBunchArray.h>
#include <sensor_msgs/PointCloud2.h>

#include "cloud_conversions.hpp"
#include "cropsight/bridge/seedling_runner.hpp"
#include "cropsight/bridge/sequence_io.hpp"
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

// A simulated broccoli pass of `n` frames in d/seq, as a bag (its frames) and as `detect
// broccoli`'s output with `model` (one JSON per frame).
void simulated_broccoli_pass(const fs::path& d, int n, int seed, const std::string& model,
                             std::vector<BagFrame>& frames, std::vector<nlohmann::json>& expected) {
  ASSERT_EQ(run(cli() + " simulate broccoli --frames " + std::to_string(n) + " --seed " + std::to_string(seed) +
                " --out " + (d / "seq").string() + " >/dev/null 2>&1"),
            0);
  ASSERT_EQ(run(cli() + " export --data " + (d / "seq").string() + " --out " + (d / "s.bag").string() + " >/dev/null"),
            0);
  ASSERT_EQ(run(cli() + " detect broccoli --data " + (d / "seq").string() + " --model " + model + " --out " +
                (d / "cli.jsonl").string() + " --quiet >/dev/null"),
            0);
  expected = read_lines(d / "cli.jsonl");
  frames = read_bag(d / "s.bag");
  ASSERT_EQ(frames.size(), expected.size());
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

// The node's heads of one frame against the CLI's detections of it (score, centroid in m).
void expect_heads_equal(const vision_msgs::Detection3DArray& msg, const nlohmann::json& cli_dets, double score_tol,
                        double position_tol, std::size_t frame) {
  ASSERT_EQ(msg.detections.size(), cli_dets.size()) << "frame " << frame;
  for (std::size_t j = 0; j < msg.detections.size(); ++j) {
    const auto& r = msg.detections[j].results.at(0);
    EXPECT_NEAR(r.score, cli_dets[j]["score"].get<double>(), score_tol) << "frame " << frame;
    const auto& p = r.pose.pose.position;
    for (int a = 0; a < 3; ++a)
      EXPECT_NEAR(a == 0   ? p.x
                  : a == 1 ? p.y
                           : p.z,
                  cli_dets[j]["centroid"][a].get<double>(), position_tol)
          << "frame " << frame << " head " << j;
  }
}

class RosNodes : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ASSERT_TRUE(ros::master::check()) << "no ROS master: run through ctest (fixture ros_master)";
  }
};

TEST_F(RosNodes, BroccoliNodeDetectionsEqualTheCli) {
  const fs::path d = scratch_dir("broccoli_node");
  const std::string model = kSource + "/models/broccoli-oes-uk.json";
  std::vector<BagFrame> frames;
  std::vector<nlohmann::json> expected;
  ASSERT_NO_FATAL_FAILURE(simulated_broccoli_pass(d, 8, 4242, model, frames, expected));

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
    EXPECT_EQ(msg.header.frame_id, frames[k].depth->header.frame_id) << "headers are copied from the input";
    expect_heads_equal(msg, expected[k]["detections"], 1e-6, 1e-6, k);
  }
  EXPECT_EQ(node.stop(), 0);
  EXPECT_TRUE(fs::exists(d / "map.csv")) << "the field map is saved on shutdown";
}

TEST_F(RosNodes, MalformedMessagesAreSkippedCountedAndTheNodeLives) {
  const fs::path d = scratch_dir("broccoli_malformed");
  ASSERT_EQ(run(cli() + " simulate broccoli --frames 2 --seed 4243 --out " + (d / "seq").string() + " >/dev/null 2>&1"),
            0);
  ASSERT_EQ(run(cli() + " export --data " + (d / "seq").string() + " --out " + (d / "s.bag").string() + " >/dev/null"),
            0);
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
  ASSERT_EQ(run(cli() + " export --data " + (d / "seq").string() + " --out " + (d / "p.bag").string() + " >/dev/null"),
            0);
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

TEST_F(RosNodes, ANodeThatCannotStartSaysWhyAndExits2) {
  const fs::path d = scratch_dir("node_bad_preset");
  for (const std::string node : {"potato", "grape"}) {
    const fs::path err = d / (node + ".err");
    EXPECT_EQ(run(kBin + "/cropsight_" + node + "_node __ns:=/bad __name:=" + node + " _preset:=no-such-preset 2>" +
                  err.string() + " >/dev/null"),
              2)
        << node;
    std::ifstream in(err);
    const std::string text((std::istreambuf_iterator<char>(in)), {});
    EXPECT_NE(text.find("cropsight_" + node + "_node: no-such-preset: no such preset"), std::string::npos) << text;
  }
}

TEST_F(RosNodes, BroccoliNodeOnOrganisedCloudsEqualsTheCli) {
  // The frames of a simulated pass as organised clouds (what depth_image_proc publishes): the
  // node turns them back into depth with fitted intrinsics, so its heads equal the CLI's on the
  // depth images (to float precision of the fit).
  const fs::path d = scratch_dir("broccoli_cloud");
  const std::string model = kSource + "/models/broccoli-oes-uk.json";
  std::vector<BagFrame> frames;
  std::vector<nlohmann::json> expected;
  ASSERT_NO_FATAL_FAILURE(simulated_broccoli_pass(d, 4, 4246, model, frames, expected));
  NodeProcess node(kBin + "/cropsight_broccoli_node",
                   {"__ns:=/b3", "__name:=broccoli", "_model:=" + model, "_input:=cloud"}, (d / "node.log").string());
  ros::NodeHandle nh;
  std::map<double, vision_msgs::Detection3DArray> got;
  ros::Subscriber sub = nh.subscribe<vision_msgs::Detection3DArray>(
      "/b3/heads", 10, [&](const vision_msgs::Detection3DArray::ConstPtr& m) { got[m->header.stamp.toSec()] = *m; });
  ros::Publisher points = nh.advertise<sensor_msgs::PointCloud2>("/b3/points", 10);
  ASSERT_TRUE(spin_until([&] { return points.getNumSubscribers() > 0; }, 30)) << "the node did not subscribe";
  int heads = 0;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const BagFrame& f = frames[k];
    cropsight::bridge::FrameBuffers fb;
    fb.camera = cropsight::ros_io::camera_from_info(*f.info, 0.001, "info");
    fb.depth = cropsight::ros_io::depth_from_image(*f.depth, fb.camera, "depth");
    sensor_msgs::PointCloud2 pc = cropsight::ros_io::organised_cloud_from_frame(fb);
    pc.header = f.depth->header;
    points.publish(pc);
    ASSERT_TRUE(spin_until([&] { return got.count(f.stamp.toSec()) > 0; }, 30)) << "no heads for frame " << k;
    const auto& msg = got[f.stamp.toSec()];
    EXPECT_EQ(msg.header.frame_id, f.depth->header.frame_id);
    expect_heads_equal(msg, expected[k]["detections"], 1e-4, 1e-5, k);
    heads += int(msg.detections.size());
  }
  EXPECT_GT(heads, 0) << "the simulated frames hold heads";
  // An unorganised cloud is skipped, counted, and the node lives.
  sensor_msgs::PointCloud2 flat = cropsight::ros_io::make_cloud({0.f, 0.f, 1.f});
  flat.header.stamp = ros::Time(99);
  points.publish(flat);
  spin_until([] { return false; }, 0.5);
  EXPECT_TRUE(node.alive());
  EXPECT_EQ(got.count(99.0), 0u);
  EXPECT_EQ(node.stop(), 0);
}

// A 160x120 RGB-D frame of a vine for the grape node: a wall at 1.5 m, a purple bunch bulging
// toward the camera at ~0.8 m under a brown peduncle, and a second, smaller bunch; colour is
// registered to depth. `boxes`: their COCO boxes (1 bunch, 2 peduncle) as x, y, w, h.
cropsight::bridge::FrameBuffers grape_frame(std::vector<std::array<int, 5>>& boxes) {
  cropsight::bridge::FrameBuffers f;
  f.camera.width = 160, f.camera.height = 120;
  f.camera.fx = f.camera.fy = 150, f.camera.cx = 80, f.camera.cy = 60;
  f.depth.assign(160 * 120, 1500);
  f.rgb.resize(3 * 160 * 120);
  auto paint = [&](int u, int v, std::uint16_t z, std::array<std::uint8_t, 3> c) {
    f.depth[std::size_t(v * 160 + u)] = z;
    for (int k = 0; k < 3; ++k) f.rgb[std::size_t(3 * (v * 160 + u) + k)] = c[std::size_t(k)];
  };
  for (int v = 0; v < 120; ++v)
    for (int u = 0; u < 160; ++u) paint(u, v, 1500, {60, 140, 50});
  auto bunch = [&](int cu, int cv, int r, int z) {
    for (int v = cv - r; v <= cv + r; ++v)
      for (int u = cu - r; u <= cu + r; ++u) {
        const int d2 = (u - cu) * (u - cu) + (v - cv) * (v - cv);
        if (d2 <= r * r) paint(u, v, std::uint16_t(z - int(std::sqrt(double(r * r - d2)) * 5)), {90, 30, 110});
      }
  };
  bunch(80, 75, 20, 800);
  for (int v = 35; v < 55; ++v)
    for (int u = 78; u <= 81; ++u) paint(u, v, 780, {120, 90, 40});
  bunch(130, 80, 10, 900);
  boxes = {{60, 55, 41, 41, 1}, {76, 33, 8, 22, 2}, {120, 70, 21, 21, 1}};
  return f;
}

TEST_F(RosNodes, GrapeNodeBunchesEqualTheCli) {
  const fs::path d = scratch_dir("grape_node");
  std::vector<std::array<int, 5>> boxes;
  cropsight::bridge::FrameBuffers frame = grape_frame(boxes);
  {
    cropsight::bridge::SequenceSink sink((d / "seq").string(), frame.camera, true);
    sink.write(frame);
    sink.finish();
  }
  nlohmann::json coco = nlohmann::json::array();
  vision_msgs::Detection2DArray det_msg;
  for (const auto& b : boxes) {
    coco.push_back({{"image_id", 0}, {"category_id", b[4]}, {"bbox", {b[0], b[1], b[2], b[3]}}, {"score", 0.9}});
    vision_msgs::Detection2D det;
    vision_msgs::ObjectHypothesisWithPose hyp;
    hyp.id = b[4];
    hyp.score = 0.9;
    det.results.push_back(hyp);
    det.bbox.center.x = b[0] + 0.5 * b[2];
    det.bbox.center.y = b[1] + 0.5 * b[3];
    det.bbox.size_x = b[2];
    det.bbox.size_y = b[3];
    det_msg.detections.push_back(det);
  }
  std::ofstream(d / "boxes.json") << coco.dump();
  const std::string segmenter = kSource + "/models/grape-gbdt-fast.json";
  const std::string files = " --color " + (d / "seq/color/000000.png").string() + " --depth " +
                            (d / "seq/depth/000000.png").string() + " --camera " + (d / "seq/camera.yaml").string() +
                            " --segmenter " + segmenter + " --threads 1";
  // Boxes from the user's detector (`detections`), and from the project's detector; then the
  // boxes again with the label the model gives most points of bunch A taken as "peduncle" (the
  // shipped models label no peduncle on this frame), so that a cut point is compared too.
  std::string set;
  for (const std::string tag : {"boxes", "detector", "cut"}) {
    const bool own_detector = tag == "detector";
    const fs::path out = d / ("cli_" + tag);
    ASSERT_EQ(run(cli() + " detect grape" + files +
                  (own_detector ? " --detector " + kSource + "/models/detector-grape.onnx"
                                : " --detections " + (d / "boxes.json").string()) +
                  (set.empty() ? "" : " --set " + set) + " --out " + out.string() + " >/dev/null"),
              0);
    std::ifstream file(out / "cut_points.json");
    const nlohmann::json e = nlohmann::json::parse(file);
    const std::string ns = "/g_" + tag;
    NodeProcess node(
        kBin + "/cropsight_grape_node",
        {"__ns:=" + ns, "__name:=grape", "_segmenter:=" + segmenter, "_threads:=1",
         "_detector:=" + (own_detector ? std::string("models/detector-grape.onnx") : "none"), "_set:=" + set},
        (d / ("node_" + tag + ".log")).string());
    ros::NodeHandle nh;
    std::map<double, cropsight_msgs::GrapeBunchArray> got;
    ros::Subscriber sub = nh.subscribe<cropsight_msgs::GrapeBunchArray>(
        ns + "/bunches", 5,
        [&](const cropsight_msgs::GrapeBunchArray::ConstPtr& m) { got[m->header.stamp.toSec()] = *m; });
    Inputs in(nh, ns, true);
    ros::Publisher dets = nh.advertise<vision_msgs::Detection2DArray>(ns + "/detections", 5);
    ASSERT_TRUE(spin_until([&] { return in.connected() && (own_detector || dets.getNumSubscribers() > 0); }, 30))
        << "the node did not subscribe";
    const ros::Time t(30);
    sensor_msgs::Image depth = cropsight::ros_io::image_from_depth(frame.depth, 160, 120);
    sensor_msgs::Image color = cropsight::ros_io::image_from_rgb(frame.rgb, 160, 120);
    sensor_msgs::CameraInfo info = cropsight::ros_io::info_from_camera(frame.camera);
    depth.header.stamp = color.header.stamp = info.header.stamp = det_msg.header.stamp = t;
    color.header.frame_id = depth.header.frame_id = info.header.frame_id = "vine_optical";
    in.color.publish(color);
    in.depth.publish(depth);
    in.info.publish(info);
    if (!own_detector) dets.publish(det_msg);
    ASSERT_TRUE(spin_until([&] { return got.count(t.toSec()) > 0; }, 60)) << tag << ": no bunches";
    const auto& msg = got[t.toSec()];
    EXPECT_EQ(msg.header.frame_id, "vine_optical");
    const auto& bunches = e["bunches"];
    ASSERT_EQ(msg.bunches.size(), bunches.size()) << tag;
    if (!own_detector) {
      EXPECT_EQ(bunches.size(), 2u) << "two bunch boxes, apart";
    }
    for (std::size_t k = 0; k < bunches.size(); ++k) {
      const auto& m = msg.bunches[k];
      const auto& b = bunches[k];
      EXPECT_EQ(std::vector<int>({m.roi_x, m.roi_y, m.roi_width, m.roi_height}), b["roi"].get<std::vector<int>>());
      ASSERT_EQ(std::size_t(m.cloud.width), b["points"].get<std::size_t>()) << tag << " bunch " << k;
      ASSERT_EQ(m.cloud.fields.size(), 5u);
      ASSERT_EQ(m.cloud.fields[4].name, "label");
      std::vector<long> counts(6, 0);
      for (std::size_t i = 0; i < m.cloud.width; ++i) {
        std::int32_t label;
        std::memcpy(&label, m.cloud.data.data() + i * m.cloud.point_step + m.cloud.fields[4].offset, 4);
        if (label >= 0 && label < 6) ++counts[std::size_t(label)];
      }
      EXPECT_EQ(counts, b["label_counts"].get<std::vector<long>>()) << tag << " bunch " << k;
      EXPECT_EQ(bool(m.has_cut_point), !b["cut_point"].is_null());
      if (m.has_cut_point) {
        EXPECT_NEAR(m.cut_position.x, b["cut_point"]["position_m"][0].get<double>(), 1e-6);
        EXPECT_NEAR(m.cut_position.z, b["cut_point"]["position_m"][2].get<double>(), 1e-6);
        EXPECT_NEAR(m.cut_direction.y, b["cut_point"]["direction"][1].get<double>(), 1e-6);
        EXPECT_EQ(m.cut_confidence, b["cut_point"]["confidence"].get<int>());
      }
    }
    if (tag == "cut") {
      EXPECT_FALSE(e["bunches"][0]["cut_point"].is_null()) << "the label with most points of A gives a cut point";
    }
    EXPECT_EQ(node.stop(), 0);
    if (tag == "boxes") {
      const auto counts = bunches[0]["label_counts"].get<std::vector<long>>();
      set = "cut_point.peduncle_label=" +
            std::to_string(std::max_element(counts.begin() + 1, counts.end()) - counts.begin());
    }
  }
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
