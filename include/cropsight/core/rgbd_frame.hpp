#pragma once
// One RGB-D frame of a sequence (see docs/formats.md).
#include <optional>

#include "cropsight/core/camera.hpp"
#include "cropsight/core/image.hpp"

namespace cropsight {

struct RgbdFrame {
  int index = 0;                                   ///< frame number in its sequence, from 0
  double timestamp = 0.0;                          ///< seconds (0 when unknown)
  CameraIntrinsics camera;                         ///< intrinsics of depth (colour is registered to depth)
  DepthImage depth;                                ///< raw units, metres = value * camera.depth_scale; 0 = no return
  ColorImage color;                                ///< empty when the sequence has no colour
  LabelImage labels;                               ///< empty when the sequence has no ground truth
  std::optional<Eigen::Vector3d> camera_position;  ///< field frame, metres (from poses.csv)
};

}  // namespace cropsight
