#include "bag_cli.hpp"

#include <filesystem>

#include "cli_common.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#if CROPSIGHT_HAS_ROS
#include "cropsight_ros/bag_io.hpp"
#endif

namespace fs = std::filesystem;

namespace cropsight::cli {

void add_bag_topic_options(CLI::App* cmd, BagTopicOptions& o) {
  cmd->add_option("--depth-topic", o.depth, "Bag topic of the 16UC1 depth images")->capture_default_str();
  cmd->add_option("--info-topic", o.camera_info, "Bag topic of the depth camera_info")->capture_default_str();
  cmd->add_option("--color-topic", o.color, "Bag topic of the colour images (registered to depth)")
      ->capture_default_str();
}

#if CROPSIGHT_HAS_ROS
namespace {
ros_io::BagTopics topics_of(const BagTopicOptions& o) {
  ros_io::BagTopics t;
  t.depth = o.depth;
  t.camera_info = o.camera_info;
  t.color = o.color;
  return t;
}
}  // namespace

BagSequence::BagSequence(const std::string& bag, const BagTopicOptions& topics) {
  // /tmp/.cropsight-bag.tmp-PID-N: the process id in the name lets the next run remove what a
  // run killed by a signal (which cannot unwind) left (kill safety).
  const fs::path name = fs::temp_directory_path() / "cropsight-bag";
  io::remove_stale_temporaries(name);
  root_ = io::temporary_sibling(name).string();
  fs::create_directories(root_);
  path_ = (fs::path(root_) / "sequence").string();
  ros_io::BagImportOptions o;
  o.bag = bag;
  o.out = path_;
  o.topics = topics_of(topics);
  try {
    ros_io::import_bag_sequence(o);
  } catch (...) {
    std::error_code ec;
    fs::remove_all(root_, ec);
    throw;
  }
}

BagExportResult export_bag(const std::string& seq, const std::string& bag, const BagTopicOptions& topics, double fps,
                           bool overwrite) {
  ros_io::BagExportOptions o;
  o.sequence = seq;
  o.bag = bag;
  o.topics = topics_of(topics);
  o.fps = fps;
  o.overwrite = overwrite;
  const auto s = ros_io::export_sequence_bag(o);
  return {s.frames, s.messages, s.color};
}

BagImportResult import_bag(const std::string& bag, const std::string& out, const BagTopicOptions& topics,
                           bool overwrite, const std::string& poses, double pose_tolerance_s,
                           const std::string& color_camera, const std::string& extrinsics) {
  ros_io::BagImportOptions o;
  o.bag = bag;
  o.out = out;
  o.topics = topics_of(topics);
  o.overwrite = overwrite;
  o.poses = poses;
  o.pose_tolerance_s = pose_tolerance_s;
  o.color_camera = color_camera;
  o.extrinsics = extrinsics;
  const auto s = ros_io::import_bag_sequence(o);
  return {s.frames, s.color, s.unmatched_color, s.skipped_without_color, s.poses_format};
}
#else
namespace {
[[noreturn]] void no_ros(const std::string& bag) {
  throw Error(bag, "this build has no ROS support (scripts/install-deps.sh installs ROS 1, then rebuild)");
}
}  // namespace
BagSequence::BagSequence(const std::string& bag, const BagTopicOptions&) { no_ros(bag); }
BagExportResult export_bag(const std::string&, const std::string& bag, const BagTopicOptions&, double, bool) {
  no_ros(bag);
}
BagImportResult import_bag(const std::string& bag, const std::string&, const BagTopicOptions&, bool, const std::string&,
                           double, const std::string&, const std::string&) {
  no_ros(bag);
}
#endif

bool is_bag_file(const std::string& path) { return fs::path(path).extension() == ".bag"; }

void add_recording_options(CLI::App* cmd, std::string& data, BagTopicOptions& topics, const std::string& help) {
  cmd->add_option("--data", data, help + ", or a ROS bag (.bag: depth, camera_info, colour topics below)");
  add_deprecated_option(cmd, "--bag", data, "--data");
  add_bag_topic_options(cmd, topics);
}

Recording::Recording(const std::string& data, const BagTopicOptions& topics) : data_(data) {
  if (data.empty()) throw Error("--data", "give a sequence folder or a ROS bag");
  if (is_bag_file(data)) bag_.emplace(data, topics);
}

BagSequence::~BagSequence() {
  std::error_code ec;
  if (!root_.empty()) fs::remove_all(root_, ec);
}

}  // namespace cropsight::cli
