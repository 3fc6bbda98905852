#pragma once
// Real recordings in (Deliver 4): folders of 16-bit depth PNGs (+ registered colour
// PNGs) or organised PCD files, plus a camera.yaml, become a sequence (sequence.hpp) with no
// ground truth, which `detect broccoli` runs on. docs/formats.md, "Importing recordings".
//
// File names: a frame's key is the last number in its file stem, so every common recorder layout
// sorts in recording order:
//   000123.png, depth_000123.png, 000123_depth.png           (Kinect v2 savers: kinect2_bridge,
//   frame-000123.depth.png                                    libfreenect2 examples, 3DMatch style)
//   _Depth_1596203844123.456.png / _Color_1596203844130.112.png  (RealSense rs-convert: the
//                                                             number is a timestamp in ms)
// Frames sort by key; two files with one key are an error. Colour (PNG or JPEG) pairs with depth
// by key when the key sets agree, else by order when the counts agree (rs-convert's colour and
// depth timestamps differ), else it is an error. Colour of another camera (another size, or any
// colour when --color-camera and --extrinsics are given) is registered to depth
// (color_registration.hpp). Timestamps: keys with a fractional part or of 10+ digits are
// milliseconds (RealSense) and become seconds from the first frame; others are frame numbers,
// timestamped index / fps, or by a --timestamps CSV (seconds from its first frame). The sequence
// keeps them (poses.csv or timestamps.csv).
// Poses (--poses, pose_track.hpp) are joined to the frames by time: to the file-name timestamps
// in seconds (ms / 1000, not shifted to the first frame), the --timestamps CSV's, or index / fps.
#include <filesystem>
#include <string>
#include <vector>

namespace cropsight::io {

struct ImportOptions {
  std::filesystem::path depth_dir;     ///< 16-bit PNGs, raw units (metres = value x camera depth_scale)
  std::filesystem::path color_dir;     ///< optional: 8-bit colour PNGs or JPEGs
  std::filesystem::path pcd_dir;       ///< alternative to depth_dir: organised .pcd files (metres, camera frame)
  std::filesystem::path camera_yaml;   ///< depth intrinsics: camera.yaml or a ROS camera_info YAML
  std::filesystem::path color_camera;  ///< colour intrinsics (same formats); with `extrinsics`, registers colour
  std::filesystem::path extrinsics;    ///< depth-to-colour transform (color_registration.hpp)
  std::filesystem::path poses;         ///< optional pose file (pose_track.hpp)
  std::filesystem::path timestamps;    ///< optional CSV of `frame` (the names' number), `timestamp` (s)
  std::filesystem::path out;
  bool overwrite = false;
  double fps = 0.0;                ///< frames per second for frame-number keys (0: timestamps 0)
  double depth_scale = 0.0;        ///< metres per depth unit; 0: the camera file's
  double pose_tolerance_s = 0.05;  ///< a frame's pose must lie within this of its time
};

struct ImportSummary {
  int frames = 0;
  bool color = false;
  bool color_registered = false;  ///< colour came from another camera and was registered to depth
  bool labels = false;            ///< the PCDs' label field became labels/
  bool timestamps_from_names = false;
  std::string time_source;   ///< "names", "csv" (--timestamps), "fps" or "none"
  std::string poses_format;  ///< "" without --poses
};

/// One numbered frame file of a recording folder.
struct RecordingFile {
  std::filesystem::path path;
  std::string key;   ///< the number as written
  double value = 0;  ///< the number
};

/// The frame files of `dir` with one of the extensions `exts` (".png", ".pcd"; case-insensitive),
/// sorted by their key; other files (a README) are not frames. Throws Error(dir, ...) when the
/// folder is missing or holds no frame, and Error(file, ...) for a name without a number or a key
/// used twice.
std::vector<RecordingFile> list_recording(const std::filesystem::path& dir, const std::vector<std::string>& exts);

/// Reads every frame (validating bit depth, channels and size against camera.yaml) and writes the
/// sequence to a temporary folder renamed to options.out when complete: a bad input leaves
/// nothing behind. Throws Error naming the offending file.
ImportSummary import_recording(const ImportOptions& options);

}  // namespace cropsight::io
