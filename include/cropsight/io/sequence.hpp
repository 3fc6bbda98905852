#pragma once
// The RGB-D sequence format (docs/formats.md):
//
//   SEQ/camera.yaml          width, height, fx, fy, cx, cy, depth_scale, [distortion], [sensor]
//   SEQ/depth/000000.png     16-bit depth, 0 = no return
//   SEQ/color/000000.png     8-bit colour registered to depth (optional)
//   SEQ/labels/000000.png    16-bit instance id per pixel, 0 = other (optional; needs depth)
//   SEQ/labelled.csv         frame: the frames labels/ holds when only some are labelled (optional)
//   SEQ/poses.csv            frame,timestamp,x,y,z camera position in the field frame (optional)
//   SEQ/timestamps.csv       frame,timestamp: frame times of a sequence without poses (optional)
//   SEQ/groundtruth.json     {"instances": [{"id", "position": [x,y,z], "diameter_mm", ...}], ...}
//
// Readers validate everything and throw cropsight::Error naming the offending file.
// Not thread-safe per object; distinct readers may be used from distinct threads.
#include <Eigen/Core>
#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cropsight/core/camera.hpp"
#include "cropsight/core/rgbd_frame.hpp"
#include "cropsight/io/geo_origin.hpp"
#include "cropsight/io/output.hpp"

namespace cropsight::io {

/// One ground-truth instance of a sequence (e.g. a broccoli head).
struct InstanceTruth {
  int id = 0;                                          ///< matches the label image value
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< field frame, metres
  double diameter_mm = 0.0;
  std::map<std::string, double> extra;  ///< other numeric truth (e.g. "height_m", "harvested")
};

struct GroundTruth {
  std::vector<InstanceTruth> instances;
  std::map<std::string, std::string> attributes;  ///< free-form sequence-level truth (variety, seed...)
  /// The instance with this id, or nullptr (a linear search: passes hold tens of instances).
  const InstanceTruth* find(int id) const {
    for (const auto& t : instances)
      if (t.id == id) return &t;
    return nullptr;
  }
};

struct CameraPose {
  int frame = 0;
  double timestamp = 0.0;                              ///< seconds
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< field frame, metres
};

struct SequenceInfo {
  std::filesystem::path dir;
  CameraIntrinsics camera;
  int frames = 0;
  bool has_color = false;
  bool has_labels = false;
  /// Frames with a label image, ascending: every frame, or those labelled.csv lists (a partly
  /// labelled sequence: the other frames have no labels, and training skips them).
  std::vector<int> labelled_frames;
  bool labelled(int index) const { return std::binary_search(labelled_frames.begin(), labelled_frames.end(), index); }
  bool has_poses = false;
  bool has_timestamps = false;  ///< timestamps.csv (poses.csv carries the times when present)
  bool has_groundtruth = false;
  /// Visible top-level entries that are no part of the format (a README, notes): ignored, and
  /// named in one notice line on stderr when the reader opens the sequence.
  std::vector<std::filesystem::path> ignored;
};

/// Reads camera.yaml, or a ROS camera_info YAML in its place (camera_calibration's file or a
/// CameraInfo message as `rostopic echo` prints it; depth_scale is then REP 118's 0.001). Throws
/// Error(path, ...) for a missing file, bad YAML or bad values, and names the accepted formats
/// for any other YAML.
CameraIntrinsics read_camera_yaml(const std::filesystem::path& path);
/// Writes camera.yaml atomically.
void write_camera_yaml(const std::filesystem::path& path, const CameraIntrinsics& camera);

class SequenceReader {
 public:
  /// Opens and validates the layout of `dir`: camera.yaml, frames numbered from 0 without gaps,
  /// colour/labels frame sets equal to the depth set, poses/timestamps/groundtruth parse. A visible
  /// entry whose name is one edit or two from a known one (groundtruth.jsn) is an error, as it is
  /// most likely a misspelling; other unknown entries are ignored with one notice line on stderr. Image contents are
  /// checked (bit depth, size) when each frame is read.
  explicit SequenceReader(std::filesystem::path dir);

  const SequenceInfo& info() const { return info_; }
  int size() const { return info_.frames; }
  /// Reads frame `index` (0-based); throws Error naming the image file on a wrong bit depth,
  /// channel count or size.
  RgbdFrame read(int index) const;
  const std::vector<CameraPose>& poses() const { return poses_; }  ///< empty when no poses.csv
  /// Seconds per frame (poses.csv's or timestamps.csv's); empty when the sequence has neither.
  const std::vector<double>& timestamps() const { return timestamps_; }
  const GroundTruth& groundtruth() const { return groundtruth_; }  ///< empty when absent

  std::filesystem::path depth_path(int index) const;
  std::filesystem::path color_path(int index) const;
  std::filesystem::path labels_path(int index) const;

 private:
  void check_timestamps(const std::filesystem::path& file);

  SequenceInfo info_;
  std::vector<CameraPose> poses_;
  std::vector<double> timestamps_;
  GroundTruth groundtruth_;
};

/// Writes a sequence. Everything goes to a temporary sibling directory that is renamed to `dir`
/// by finish(); a writer destroyed without finish() removes its temporary directory, so an
/// interrupted run never leaves a sequence that looks complete.
class SequenceWriter {
 public:
  /// Checks `dir` as an output folder of `policy` before anything is written (io/output.hpp:
  /// never an input, never a folder cropsight did not write, an earlier output only with force)
  /// and throws Error(dir, ...) when it may not be written.
  SequenceWriter(std::filesystem::path dir, CameraIntrinsics camera, const OutputPolicy& policy);
  /// The same for a writer of no particular command: `overwrite` is the policy's force.
  SequenceWriter(std::filesystem::path dir, CameraIntrinsics camera, bool overwrite = false);
  ~SequenceWriter();
  SequenceWriter(const SequenceWriter&) = delete;
  SequenceWriter& operator=(const SequenceWriter&) = delete;

  /// Frames must arrive in order 0, 1, 2, ...; colour/labels presence must not change.
  void write(const RgbdFrame& frame);
  void set_groundtruth(GroundTruth truth);
  /// Writes geo_origin.yaml with the sequence (io/geo_origin.hpp): where its field frame lies on the Earth.
  void set_geo_origin(const GeoOrigin& origin);
  /// Writes poses.csv (from frames' camera_position and timestamp), groundtruth.json, then renames.
  void finish();

 private:
  std::filesystem::path dir_, tmp_;
  std::unique_ptr<OutputFolder> out_;
  CameraIntrinsics camera_;
  int next_ = 0;
  bool color_ = false, labels_ = false, finished_ = false;
  std::vector<CameraPose> poses_;
  std::vector<double> timestamps_;
  std::optional<GroundTruth> truth_;
  std::optional<GeoOrigin> geo_origin_;
};

/// Frame file name: zero-padded to six digits, e.g. 000042.png.
std::string frame_file_name(int index);

}  // namespace cropsight::io
