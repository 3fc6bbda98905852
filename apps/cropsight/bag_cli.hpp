#pragma once
// --bag options of the CLI (issue 25): bag topics, and a sequence folder made from a bag for the
// commands that read sequences (detect broccoli, harvest potato, eval ...). Works without a ROS
// master; in a build without ROS (-DCROPSIGHT_ROS=OFF or no ROS packages) every --bag is an
// error that says so.
#include <CLI/CLI.hpp>
#include <memory>
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

/// cropsight export SEQ --bag OUT.bag and cropsight import --bag IN.bag --out SEQ
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
};
BagImportResult import_bag(const std::string& bag, const std::string& out, const BagTopicOptions& topics,
                           bool overwrite);

}  // namespace cropsight::cli
