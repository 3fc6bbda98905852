#pragma once
// Ground truth of a potato sequence (`cropsight simulate potato` writes it; a user's own recording
// can carry the same files): per frame, every potato's centre, axes, image angle and visible box,
// from groundtruth.json (instances with extras length_m, width_m, axis_x/y/z, target), poses.csv
// (the camera's position) and labels/ (instance ids per pixel). Frames: the sequence's world frame
// (docs/formats.md: x down, y right, z toward the camera, metres) and the camera frame (x right,
// y down, z forward), related by the nadir convention camera x = world y, camera y = world x,
// camera z = -world z. Reading truth is all this file does: evaluation is eval.hpp.
#include <Eigen/Core>
#include <filesystem>
#include <vector>

#include "cropsight/core/camera.hpp"
#include "cropsight/core/detection2d.hpp"
#include "cropsight/core/image.hpp"
#include "cropsight/io/sequence.hpp"

namespace cropsight::pipeline::potato {

/// One frame's truth of one potato.
struct FrameTruth {
  int id = 0;
  bool target = false;                                      ///< the potato the approach goes for
  Eigen::Vector3d centre_world = Eigen::Vector3d::Zero();   ///< world frame, m
  Eigen::Vector3d centre_camera = Eigen::Vector3d::Zero();  ///< camera frame, m
  double length_m = 0, width_m = 0;                         ///< ellipsoid's full axes
  double angle_rad = 0;  ///< length axis in the image, counter-clockwise from image x, [0, pi)
  Detection2D box;       ///< visible pixels' box (labels), continuous pixel coordinates
  int visible_pixels = 0;
};

/// The truth of every potato in one frame: centres from the instances and the camera position,
/// the angle by projecting the length axis, boxes from the label image.
std::vector<FrameTruth> frame_truth(const io::GroundTruth& truth, const Eigen::Vector3d& camera_position,
                                    const CameraIntrinsics& camera, const LabelImage& labels);

/// The truth of frame `f` of `reader`'s sequence `seq`. Throws Error(file, ...) when the frame
/// has no pose.
std::vector<FrameTruth> frame_truth(const io::SequenceReader& reader, const RgbdFrame& f,
                                    const std::filesystem::path& seq);

/// Throws Error(file, ...) unless the sequence carries per-potato instances, poses and labels.
void require_truth(const io::SequenceReader& reader, const std::filesystem::path& seq);

/// An approach in memory: colour frames and the truth of every potato per frame.
struct TruthSequence {
  std::vector<ColorImage> colour;
  std::vector<std::vector<FrameTruth>> truth;  ///< per frame
};

/// Reads the colour frames and the per-frame truth of a sequence with potato truth.
/// Throws Error(file, ...) when it is unreadable or lacks the truth.
TruthSequence read_truth_sequence(const std::filesystem::path& seq);

}  // namespace cropsight::pipeline::potato
