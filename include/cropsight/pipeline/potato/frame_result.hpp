#pragma once
// What the potato pipeline returns for one frame (Pipeline::process, pipeline.hpp): the harvest
// message and what led to it. Plain C++17 data, so that the ROS node (built as C++17) uses it as it
// is. Units: metres and radians, camera frame (x right, y down, z forward); boxes in pixels.
#include <optional>
#include <vector>

#include "cropsight/core/box2d.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/measure/position_result.hpp"
#include "cropsight/tracking/target_state.hpp"

namespace cropsight::pipeline::potato {

/// The harvest message (paper Table 3.2: detection, depth_ok, x, y, z, height, width, angle) plus
/// what a controller or a log needs to follow it.
struct HarvestTarget {
  int frame = 0;
  double timestamp = 0;         ///< s, from the frame
  bool detection = false;       ///< a target is in view this frame (detected or tracked)
  bool depth_ok = false;        ///< its depth is usable (within range, enough valid pixels)
  float x = 0, y = 0, z = 0;    ///< m, camera frame (x right, y down, z forward)
  float height = 0, width = 0;  ///< m, box sides at the potato's depth
  float angle = 0;              ///< rad, length axis, counter-clockwise from the image x axis, [0, π)
  bool angle_ok = false;        ///< the orientation step found the potato in the box
  bool cut = false;             ///< the box touches the image border: x, y, z are of the visible part
  int target_id = 0;            ///< 1, 2, ... per selected target; 0 = none
  tracking::TargetState state = tracking::TargetState::selecting;
  float score = 0;  ///< detector score of the target's box (0 when tracked)
  Detection2D box;  ///< pixels
};

/// Everything one frame produced (the message and what led to it).
struct FrameResult {
  std::vector<Detection2D> detections;
  std::vector<measure::Position3D> positions;  ///< one per detection
  std::vector<bool> ripe;                      ///< one per detection
  HarvestTarget target;
  StageTimer timer;  ///< this frame's wall-clock stages: detect, locate (with ripeness), track, orient
};

/// What steps 1 and 5 found on one single image (Pipeline::detect_image; `detect potato`).
struct ImageResult {
  std::vector<Detection2D> detections;
  /// When asked for: one per detection, its length axis (rad, counter-clockwise from the image x
  /// axis), none where step 5 found no potato in the box. Empty when not asked for.
  std::vector<std::optional<double>> angles;
  StageTimer timer;  ///< wall-clock stages: detect, orient (when asked for)
};

}  // namespace cropsight::pipeline::potato
