#pragma once
// A simulated pass written out the way real recorders write it, for the import round trips:
// depth PNGs under recorder names, colour as JPEG from a second camera of another resolution
// (rendered from the pass's registered colour through known extrinsics with OpenCV's own
// projection, cv::projectPoints, so that the importer's projection is not checked against itself),
// camera_info YAMLs for both cameras, extrinsics and a pose file.
#include <filesystem>
#include <string>
#include <vector>

#include "cropsight/io/sequence.hpp"

namespace cropsight::testing {

enum class Recorder { RealSense, Kinect };

struct RecorderLayout {
  std::filesystem::path depth_dir, color_dir, depth_info, color_info, extrinsics, poses;
  std::string extra_args;  ///< e.g. "--timestamps FILE" for frame-numbered names
};

/// Writes `seq`'s frames under `dir` in the layout of `recorder`:
///   RealSense (rs-convert): _Depth_<ms>.png, _Color_<ms>.jpg 640x480 (other stamps), depth
///     camera_info as `rostopic echo` prints it, colour as camera_calibration writes it,
///     depth_to_color extrinsics, a poses CSV (absolute seconds, poses between the frames too);
///   Kinect (kinect2_bridge saver): 0000_depth.png, 0000_color.jpg 960x540, the camera files the
///     other way round, color_to_depth extrinsics, a TUM trajectory, frame numbers with their Unix
///     times in a timestamps CSV (--timestamps).
/// A README.txt beside the depth images is no frame.
RecorderLayout write_recorder_layout(const io::SequenceReader& seq, const std::filesystem::path& dir,
                                     Recorder recorder);

}  // namespace cropsight::testing
