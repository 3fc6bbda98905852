#pragma once
// Evaluation of a harvest run against the potato simulator's truth (issue 22): per frame, the
// run's target (box, 3D position, size, angle, state) is matched to the simulated potato whose
// visible box overlaps it most (IoU >= min_iou); the figures are position error per camera axis
// (mean, MAE, std, mm), size and angle errors, target switches (a target id that changes potato),
// frames with a target and lost events. Online figures: each frame is judged on its own.
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "cropsight/core/detection2d.hpp"
#include "cropsight/sim/potato/potato_sim.hpp"
#include "cropsight/tracking/target_tracker.hpp"

namespace cropsight::pipeline {

/// What a harvest run reports for one frame.
struct PotatoFrameResult {
  tracking::TargetState state = tracking::TargetState::selecting;
  int target_id = 0;
  std::optional<Detection2D> box;
  bool depth_ok = false;
  Eigen::Vector3f xyz = Eigen::Vector3f::Zero();  ///< camera frame, m
  float width_m = 0, height_m = 0;
  std::optional<double> angle_rad;  ///< length axis, [0, pi), when estimated
};

struct AxisError {
  double mean_mm = 0, mae_mm = 0, std_mm = 0;
};

struct PotatoEvaluation {
  int frames = 0, frames_with_target = 0, frames_matched = 0, frames_positioned = 0;
  int target_switches = 0, lost_events = 0, targets = 0;
  AxisError x, y, z;
  double length_mae_mm = 0, width_mae_mm = 0;  ///< box's longer / shorter metric side vs the potato's axes
  double angle_mae_deg = 0;                    ///< modulo 180 deg
  int angles = 0;
};

/// Smallest difference of two undirected axis angles, radians, in [0, pi/2].
double axis_angle_error(double a, double b);

/// Scores `run` (one entry per frame) against `truth` (potato_frame_truth of each frame).
PotatoEvaluation evaluate_potato_run(const std::vector<PotatoFrameResult>& run,
                                     const std::vector<std::vector<sim::PotatoFrameTruth>>& truth,
                                     double min_iou = 0.3);

}  // namespace cropsight::pipeline
