#pragma once
// Sequence folders <-> ROS 1 bag files, without a ROS master. Valid C++17 and C++20
// with standard types only, so that the C++20 CLI calls it without seeing a ROS header.
//
// A bag holds per frame, all stamped with the frame's time (timestamp, or index / fps when the
// sequence has no timestamps; ROS time 0 is not allowed in a bag, so stamps start at `start_s`).
// Imported frames are timed from the first depth frame's stamp, as folder imports are:
//   depth        sensor_msgs/Image 16UC1 (the raw sensor units; REP 118's millimetres when
//                depth_scale = 0.001 — any other scale is refused, as no ROS field carries it)
//   camera_info  sensor_msgs/CameraInfo (K, plumb_bob D, size) of the depth image
//   color        sensor_msgs/Image rgb8, registered to depth (when the sequence has colour)
//   /tf          tf2_msgs/TFMessage: field_frame -> frame_id, the camera position of poses.csv
//                (when the sequence has poses; translation only, as poses.csv has no rotation)
// Not carried: camera.yaml's free-text `sensor`, ground truth and label images.
// Errors: cropsight::Error (cropsight/core/error.hpp) naming the file and the problem.
#include <string>

namespace cropsight::ros_io {

/// Topic names in a bag (also the node's input names after remapping; see docs/ros.md).
struct BagTopics {
  std::string depth = "/camera/depth/image_raw";
  std::string camera_info = "/camera/depth/camera_info";
  std::string color = "/camera/color/image_raw";
  std::string tf = "/tf";
  std::string frame_id = "camera_depth_optical_frame";  ///< header.frame_id written by export
  std::string field_frame = "field";                    ///< the poses' parent frame in /tf
};

struct BagExportOptions {
  std::string sequence;  ///< input sequence folder
  std::string bag;       ///< output .bag; written to a temporary name, then renamed
  BagTopics topics;
  double fps = 30.0;       ///< frame rate for sequences without timestamps
  double start_s = 1.0;    ///< ROS time of a timestamp of 0
  bool overwrite = false;  ///< replace an existing bag
};

struct BagExportSummary {
  int frames = 0;
  long messages = 0;
  bool color = false;
};

/// Writes every frame of `o.sequence` to `o.bag`. Throws Error naming the file.
BagExportSummary export_sequence_bag(const BagExportOptions& o);

struct BagImportOptions {
  std::string bag;  ///< input .bag
  std::string out;  ///< output sequence folder (written whole through a temporary sibling)
  BagTopics topics;
  bool overwrite = false;
  double max_skew_s = 0.005;  ///< colour is matched to the depth frame whose stamp is within this
  /// A pose file (CSV or TUM, cropsight/io/pose_track.hpp) joined to the depth stamps, in place of
  /// the /tf poses; empty: the bag's /tf.
  std::string poses;
  double pose_tolerance_s = 0.05;  ///< a frame's pose must lie within this of its stamp
  /// Colour of another size than depth (unaligned streams): its intrinsics (camera.yaml or ROS
  /// camera_info YAML) and the depth-to-colour extrinsics YAML (cropsight/io/color_registration.hpp);
  /// both or neither. Each colour image is then registered to its depth frame.
  std::string color_camera, extrinsics;
};

struct BagImportSummary {
  int frames = 0;
  bool color = false;
  int unmatched_color = 0;        ///< colour images with no depth frame within max_skew_s
  int skipped_without_color = 0;  ///< depth frames left out because their colour image is missing
  std::string poses_format;       ///< the --poses file's format ("csv", "tum"); "" without
};

/// Reads depth, camera info and colour from `o.bag` into a sequence folder, as a stream: a first
/// pass collects stamps, camera info and poses, a second writes each frame as soon as its depth
/// and colour have been read, so memory does not grow with the bag's length. When the bag has
/// colour, depth frames without a colour image within max_skew_s are skipped and counted. Throws
/// Error naming the bag (a missing topic, inconsistent camera info, a wrong encoding, a truncated
/// file).
BagImportSummary import_bag_sequence(const BagImportOptions& o);

}  // namespace cropsight::ros_io
