#pragma once
// What the broccoli pipeline returns for one frame (Pipeline::process, pipeline.hpp). Plain data
// in C++17 (Eigen and the standard library only), so that the ROS nodes, built as C++17, use it as
// it is. Units: metres, camera frame (x right, y down, z forward); pixels for boxes and indices.
#include <vector>

#include "cropsight/core/detection.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/tracking/track_results.hpp"

namespace cropsight::pipeline::broccoli {

/// What process() found in one frame.
struct FrameResult {
  int frame = 0;
  /// Heads, best score first. With tracking: size_m (0 = not measured: cut by the border) and
  /// track_id (the field map's head id) are set.
  std::vector<Detection> detections;
  std::vector<tracking::PredictedHead> predicted;  ///< tracking: heads of T this frame missed
  tracking::FrameAssociation association;          ///< tracking: the filter's update (camera estimate)
  /// This frame's wall-clock stages: the detector's (denoise, normals, edges, clustering, cloud,
  /// features, classify, split, completion, cnn: those that ran) and "track" (steps 2-4).
  StageTimer timer;
  double detect_ms() const { return timer.total_ms() - timer.ms("track"); }  ///< step 1
  double track_ms() const { return timer.ms("track"); }                      ///< steps 2-4
};

}  // namespace cropsight::pipeline::broccoli
