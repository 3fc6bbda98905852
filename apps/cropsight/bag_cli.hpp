#pragma once
// ROS bags on the command line: --data takes a bag (*.bag) wherever it takes a recording, with the
// bag's topics, and a sequence folder is made from it for the commands that read sequences
// (detect broccoli, harvest potato, import). Works without a ROS master; in a build without ROS
// (-DCROPSIGHT_ROS=OFF or no ROS packages) a bag is an error that says so.
#include <CLI/CLI.hpp>
#include <memory>
#include <optional>
#include <string>

namespace cropsight::cli {

struct BagTopicOptions {
  std::string depth = "/camera/depth/image_raw";
  std::string camera_info = "/camera/depth/camera_info";
  std::string color = "/camera/color/image_raw";
};

/// --depth-topic, --info-topic, --color-topic.
void add_bag_topic_options(CLI::App* cmd, BagTopicOptions& o);

/// The frames of a bag as a sequence folder in a temporary directory, removed when this object
/// is destroyed. Throws Error(bag, ...) for a bag that cannot be read.
class BagSequence {
 public:
  BagSequence(const std::string& bag, const BagTopicOptions& topics);
  ~BagSequence();
  const std::string& path() const { return path_; }

 private:
  std::string root_, path_;
};

/// True when `path` names a ROS bag (a file ending in .bag) rather than a sequence folder.
bool is_bag_file(const std::string& path);

/// --data of a command that reads a recording: a sequence folder or a ROS bag (*.bag), with the
/// bag's topic options; --bag stays as its deprecated spelling.
void add_recording_options(CLI::App* cmd, std::string& data, BagTopicOptions& topics, const std::string& help);

/// The sequence folder a --data names: the folder itself, or a bag's frames in a temporary
/// sequence (BagSequence) that lives as long as this object. Throws Error("--data", ...) when
/// `data` is empty.
class Recording {
 public:
  Recording(const std::string& data, const BagTopicOptions& topics);
  const std::string& sequence() const { return bag_ ? bag_->path() : data_; }

 private:
  std::string data_;
  std::optional<BagSequence> bag_;
};

/// cropsight export --data SEQ --out OUT.bag and cropsight import --data IN.bag --out SEQ
/// (ros/include/cropsight_ros/bag_io.hpp).
struct BagExportResult {
  int frames = 0;
  long messages = 0;
  bool color = false;
};
BagExportResult export_bag(const std::string& seq, const std::string& bag, const BagTopicOptions& topics, double fps,
                           bool overwrite);
struct BagImportResult {
  int frames = 0;
  bool color = false;
  int unmatched_color = 0;
  int skipped_without_color = 0;
  std::string poses_format;  ///< "" without a pose file
};
/// `poses` (may be empty): a pose file joined to the depth stamps within `pose_tolerance_s`;
/// `color_camera` and `extrinsics` (both or neither): colour of another size registered to depth.
BagImportResult import_bag(const std::string& bag, const std::string& out, const BagTopicOptions& topics,
                           bool overwrite, const std::string& poses = "", double pose_tolerance_s = 0.05,
                           const std::string& color_camera = "", const std::string& extrinsics = "");

}  // namespace cropsight::cli
