// bench_ros_latency: plays a bag's frames into a running cropsight node at a fixed rate, each
// stamped with the wall-clock time it is published, and measures per message the latency
// (output received − input stamp: conversion, pipeline, transport both ways) and the input
// frames that never produced an output (dropped). It reads the node's own pipeline time
// (pipeline_ms_p50 / _p99 on `diagnostics`) at the end, so both come from the same run.
// scripts/bench-ros.sh starts the master and the node (pinned to one core) and runs this.
// It also checks that the node's output does not drift: the bag's frames are played in a loop,
// and every output's detections (count, positions to 0.1 mm, scores to 1e-4; not the sizes or
// ids, which depend on the track's history by design) must equal those of the first output for
// the same bag frame ("differing" counts those that do not). scripts/ros-long-run.sh uses this
// for the 30-minute run.
//
// Usage: bench_ros_latency --bag B --ns /camera --node broccoli|potato [--rate 30] [--frames 300]
//        [--warmup 20]
//        bench_ros_latency --stereo DIR --ns /stereo --node seedling [...]
// The seedling node takes rectified stereo pairs (left/right image_rect_color and camera_info, as
// stereo_image_proc publishes them): --stereo is a `cropsight simulate seedling` folder, whose
// pairs are rectified with its rig.yaml as `detect seedling` does.
#include <cropsight_msgs/HarvestTarget.h>
#include <diagnostic_msgs/DiagnosticArray.h>
#include <ros/ros.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <vision_msgs/Detection2DArray.h>
#include <vision_msgs/Detection3DArray.h>

#include <algorithm>
#include <cmath>
#include <cropsight/bridge/seedling_runner.hpp>
#include <cropsight/core/statistics.hpp>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "ros_conversions.hpp"

namespace {

struct Frame {
  sensor_msgs::Image depth, color, left, right;
  sensor_msgs::CameraInfo info, left_info, right_info;
  bool has_color = false;
};

// The pairs of a `simulate seedling` folder (pair_*/left.png, right.png; rig.yaml), rectified.
std::vector<Frame> stereo_frames(const std::string& dir) {
  namespace fs = std::filesystem;
  std::vector<fs::path> pairs;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_directory() && e.path().filename().string().rfind("pair_", 0) == 0) pairs.push_back(e.path());
  std::sort(pairs.begin(), pairs.end());
  std::vector<Frame> frames;
  for (const fs::path& pair : pairs) {
    const auto rect = cropsight::bridge::read_rectified_pair(
        (fs::path(dir) / "rig.yaml").string(), (pair / "left.png").string(), (pair / "right.png").string());
    const auto& g = rect.geometry;
    Frame f;
    f.left_info.width = f.right_info.width = std::uint32_t(g.width);
    f.left_info.height = f.right_info.height = std::uint32_t(g.height);
    f.left_info.P = {g.f, 0, g.cx, 0, 0, g.f, g.cy, 0, 0, 0, 1, 0};
    f.right_info.P = {g.f, 0, g.cx_right, -g.f * g.baseline, 0, g.f, g.cy, 0, 0, 0, 1, 0};
    f.left = cropsight::ros_io::image_from_rgb(rect.left.rgb, g.width, g.height);
    f.right = cropsight::ros_io::image_from_rgb(rect.right.rgb, g.width, g.height);
    frames.push_back(std::move(f));
  }
  return frames;
}

double percentile(const std::vector<double>& v, double q) { return v.empty() ? 0.0 : cropsight::quantile(v, q); }

}  // namespace

// Long on purpose: one benchmark script read top to bottom: options, node start-up, the paced publish loop, the report.
int main(int argc, char** argv) {
  ros::init(argc, argv, "cropsight_latency_bench", ros::init_options::AnonymousName);
  std::string bag_path, stereo_dir, ns = "/camera", node = "broccoli";
  double rate = 30;
  int frames = 300, warmup = 20;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i], v = argv[i + 1];
    if (k == "--bag")
      bag_path = v;
    else if (k == "--stereo")
      stereo_dir = v;
    else if (k == "--ns")
      ns = v;
    else if (k == "--node")
      node = v;
    else if (k == "--rate")
      rate = std::stod(v);
    else if (k == "--frames")
      frames = std::stoi(v);
    else if (k == "--warmup")
      warmup = std::stoi(v);
    else {
      std::fprintf(stderr, "bench_ros_latency: unknown option %s\n", k.c_str());
      return 2;
    }
  }
  const bool stereo = node == "seedling";
  if ((stereo ? stereo_dir.empty() : bag_path.empty()) || (node != "broccoli" && node != "potato" && !stereo) ||
      !(rate > 0) || frames <= warmup) {
    std::fprintf(stderr,
                 "usage: bench_ros_latency --bag B --ns NS --node broccoli|potato [--rate 30] [--frames 300]\n"
                 "       bench_ros_latency --stereo DIR --ns NS --node seedling [--rate 30] [--frames 300]\n");
    return 2;
  }
  std::vector<Frame> bag_frames;
  if (stereo) try {
      bag_frames = stereo_frames(stereo_dir);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", stereo_dir.c_str(), e.what());
      return 2;
    }
  else
    try {
      rosbag::Bag bag(bag_path, rosbag::bagmode::Read);
      std::map<ros::Time, Frame> by_time;
      for (const rosbag::MessageInstance& m : rosbag::View(bag)) {
        Frame& f = by_time[m.getTime()];
        if (m.getTopic() == "/camera/depth/image_raw") f.depth = *m.instantiate<sensor_msgs::Image>();
        if (m.getTopic() == "/camera/depth/camera_info") f.info = *m.instantiate<sensor_msgs::CameraInfo>();
        if (m.getTopic() == "/camera/color/image_raw")
          f.color = *m.instantiate<sensor_msgs::Image>(), f.has_color = true;
      }
      for (auto& [t, f] : by_time) bag_frames.push_back(f);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", bag_path.c_str(), e.what());
      return 2;
    }
  if (bag_frames.empty()) {
    std::fprintf(stderr, "%s: no frames\n", (stereo ? stereo_dir : bag_path).c_str());
    return 2;
  }
  ros::NodeHandle nh;
  auto depth_pub = nh.advertise<sensor_msgs::Image>(ns + "/depth/image_raw", 100);
  auto info_pub = nh.advertise<sensor_msgs::CameraInfo>(ns + "/depth/camera_info", 100);
  auto color_pub = nh.advertise<sensor_msgs::Image>(ns + "/color/image_raw", 100);
  ros::Publisher left_pub, right_pub, left_info_pub, right_info_pub;
  if (stereo) {
    left_pub = nh.advertise<sensor_msgs::Image>(ns + "/left/image_rect_color", 100);
    right_pub = nh.advertise<sensor_msgs::Image>(ns + "/right/image_rect_color", 100);
    left_info_pub = nh.advertise<sensor_msgs::CameraInfo>(ns + "/left/camera_info", 100);
    right_info_pub = nh.advertise<sensor_msgs::CameraInfo>(ns + "/right/camera_info", 100);
  }
  std::map<double, double> received;             // input stamp (s) -> latency (ms)
  std::map<double, std::size_t> source_of;       // input stamp (s) -> bag frame index
  std::map<std::size_t, std::string> first_out;  // bag frame index -> its first output's signature
  int differing = 0;
  auto on_output = [&](const std_msgs::Header& h, const std::string& signature) {
    received[h.stamp.toSec()] = (ros::Time::now() - h.stamp).toSec() * 1e3;
    const auto src = source_of.find(h.stamp.toSec());
    if (src == source_of.end()) return;
    const auto [first, inserted] = first_out.emplace(src->second, signature);
    if (!inserted && first->second != signature) ++differing;
  };
  auto rounded = [](double v, double unit) { return std::to_string(std::llround(v / unit)) + ","; };
  // The outputs with TCP_NODELAY, as a latency-sensitive consumer (an arm's controller) subscribes.
  auto position = [&](const geometry_msgs::Point& p) {
    return rounded(p.x, 1e-4) + rounded(p.y, 1e-4) + rounded(p.z, 1e-4);
  };
  ros::Subscriber out_sub;
  if (node == "broccoli")
    out_sub = nh.subscribe<vision_msgs::Detection3DArray>(
        ns + "/heads", 100,
        [&](const vision_msgs::Detection3DArray::ConstPtr& m) {
          std::string sig = std::to_string(m->detections.size()) + ":";
          for (const auto& d : m->detections)
            for (const auto& r : d.results) sig += position(r.pose.pose.position) + rounded(r.score, 1e-4);
          on_output(m->header, sig);
        },
        ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
  else if (node == "potato")
    out_sub = nh.subscribe<vision_msgs::Detection2DArray>(
        ns + "/detections", 100,
        [&](const vision_msgs::Detection2DArray::ConstPtr& m) {
          std::string sig = std::to_string(m->detections.size()) + ":";
          for (const auto& d : m->detections) {
            sig += rounded(d.bbox.center.x, 0.01) + rounded(d.bbox.center.y, 0.01) + rounded(d.bbox.size_x, 0.01) +
                   rounded(d.bbox.size_y, 0.01);
            for (const auto& r : d.results) sig += rounded(r.score, 1e-4);
          }
          on_output(m->header, sig);
        },
        ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
  else  // seedling: one pair at a time, no history, so the envelope's size must repeat too
    out_sub = nh.subscribe<vision_msgs::Detection3DArray>(
        ns + "/seedlings", 100,
        [&](const vision_msgs::Detection3DArray::ConstPtr& m) {
          std::string sig = std::to_string(m->detections.size()) + ":";
          for (const auto& d : m->detections)
            sig += position(d.bbox.center.position) + rounded(d.bbox.size.x, 1e-4) + rounded(d.bbox.size.y, 1e-4) +
                   rounded(d.bbox.size.z, 1e-4);
          on_output(m->header, sig);
        },
        ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
  double node_p50 = 0, node_p99 = 0;
  ros::Subscriber diag = nh.subscribe<diagnostic_msgs::DiagnosticArray>(
      ns + "/diagnostics", 10, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
        for (const auto& st : m->status)
          for (const auto& kv : st.values) {
            if (kv.key == "pipeline_ms_p50") node_p50 = std::stod(kv.value);
            if (kv.key == "pipeline_ms_p99") node_p99 = std::stod(kv.value);
          }
      });
  const bool color = node == "potato";
  auto subscribed = [&] {
    if (stereo)
      return left_pub.getNumSubscribers() > 0 && right_pub.getNumSubscribers() > 0 &&
             left_info_pub.getNumSubscribers() > 0 && right_info_pub.getNumSubscribers() > 0;
    return depth_pub.getNumSubscribers() > 0 && info_pub.getNumSubscribers() > 0 &&
           (!color || color_pub.getNumSubscribers() > 0);
  };
  const ros::WallTime wait_end = ros::WallTime::now() + ros::WallDuration(60);
  while (ros::ok() && ros::WallTime::now() < wait_end && !subscribed()) {
    ros::spinOnce();
    ros::WallDuration(0.01).sleep();
  }
  if (!subscribed()) {
    std::fprintf(stderr, "bench_ros_latency: no node subscribed to every input under %s within 60 s\n", ns.c_str());
    return 1;
  }
  std::vector<double> stamps;
  // Outputs are taken as they arrive (callbacks served every 0.2 ms between publications), so a
  // latency is not rounded up to the next publication.
  const ros::WallDuration period(1.0 / rate);
  ros::WallTime next = ros::WallTime::now();
  for (int i = 0; i < frames && ros::ok(); ++i) {
    Frame f = bag_frames[std::size_t(i) % bag_frames.size()];
    const ros::Time now = ros::Time::now();
    if (stereo) {
      f.left.header.stamp = f.right.header.stamp = f.left_info.header.stamp = f.right_info.header.stamp = now;
      left_pub.publish(f.left);
      right_pub.publish(f.right);
      left_info_pub.publish(f.left_info);
      right_info_pub.publish(f.right_info);
    } else {
      f.depth.header.stamp = f.info.header.stamp = f.color.header.stamp = now;
      if (color) color_pub.publish(f.color);
      depth_pub.publish(f.depth);
      info_pub.publish(f.info);
    }
    stamps.push_back(now.toSec());
    source_of[now.toSec()] = std::size_t(i) % bag_frames.size();
    next += period;
    while (ros::ok() && ros::WallTime::now() < next) {
      ros::spinOnce();
      ros::WallDuration(0.0002).sleep();
    }
  }
  const ros::WallTime drain = ros::WallTime::now() + ros::WallDuration(3.0);
  while (ros::ok() && ros::WallTime::now() < drain) {
    ros::spinOnce();
    ros::WallDuration(0.01).sleep();
  }
  std::vector<double> lat;
  int dropped = 0;
  for (int i = warmup; i < int(stamps.size()); ++i) {
    auto it = received.find(stamps[std::size_t(i)]);
    if (it == received.end())
      ++dropped;
    else
      lat.push_back(it->second);
  }
  std::printf(
      "{\"node\":\"%s\",\"rate_hz\":%.1f,\"frames\":%d,\"measured\":%d,\"dropped\":%d,"
      "\"latency_ms_p50\":%.2f,\"latency_ms_p99\":%.2f,\"pipeline_ms_p50\":%.2f,\"pipeline_ms_p99\":%.2f,"
      "\"overhead_ms_p99\":%.2f,\"differing\":%d}\n",
      node.c_str(), rate, frames, int(stamps.size()) - warmup, dropped, percentile(lat, 0.5), percentile(lat, 0.99),
      node_p50, node_p99, percentile(lat, 0.99) - node_p99, differing);
  return 0;
}
