#pragma once
// Figures of a harvest run against the potato simulator's truth: per frame, the
// run's target (box, 3D position, size, angle, state; what Pipeline::process returned) is
// matched to the simulated potato whose visible box overlaps it most (IoU >= min_iou); the figures
// are position error per camera axis (mean, MAE, std, mm), size and angle errors, target switches
// (a target id that changes potato), frames with a target, lost events, and the pipeline's
// milliseconds per frame per stage. Online figures: each frame is judged on what the pipeline
// reported at that frame (nothing looks ahead).
#include <filesystem>
#include <map>
#include <vector>

#include "cropsight/pipeline/potato/pipeline.hpp"
#include "cropsight/pipeline/potato/truth.hpp"

namespace cropsight::pipeline::potato {

struct AxisError {
  double mean_mm = 0, mae_mm = 0, std_mm = 0;
};

/// One frame's score (the rows behind the figures).
struct FrameScore {
  int frame = 0;
  int potato = 0;          ///< id of the simulated potato the target's box matched; 0 = none
  bool on_target = false;  ///< ... the simulator's target
  float iou = 0;
  bool positioned = false;                             ///< depth_ok: the errors below are set
  bool cut = false;                                    ///< the box touches the image border
  Eigen::Vector3d error_mm = Eigen::Vector3d::Zero();  ///< reported - true centre, camera frame
  double true_z_m = 0;                                 ///< the matched potato's centre depth
  double angle_error_deg = -1;                         ///< -1: no angle
};

struct Figures {
  int frames = 0;
  int frames_with_target = 0;     ///< frames whose message has a box (detected or tracked)
  int frames_matched = 0;         ///< ... that overlap a simulated potato (IoU >= min_iou)
  int frames_positioned = 0;      ///< ... with depth_ok and a box in full view (these give x, y, z and sizes)
  int frames_cut = 0;             ///< ... with depth_ok but a box cut by the image border (these give `cut`)
  int frames_on_target = 0;       ///< matched to the simulator's target potato (the one approached)
  int target_switches = 0;        ///< a target id whose matched potato changes
  int lost_events = 0;            ///< frames in state lost (a target dropped)
  int targets = 0;                ///< distinct target ids that matched a potato
  AxisError x, y, z;              ///< camera frame, mm, frames in full view
  AxisError cut_x, cut_y, cut_z;  ///< the same over the frames whose box the image border cuts
  double length_mae_mm = 0, width_mae_mm = 0;  ///< box's longer / shorter metric side vs the potato's axes
  double angle_mae_deg = 0;                    ///< modulo 180 deg
  int angles = 0;                              ///< frames with an angle (angle_ok)
  /// The same over the frames whose box the image border does not cut: the angle of a potato seen in
  /// part is the visible part's, and an arm grips only a potato in full view.
  double angle_mae_full_view_deg = 0;
  int angles_full_view = 0;
  std::vector<FrameScore> per_frame;  ///< one per frame
};

/// Milliseconds per frame of each stage of Pipeline::process, means over the frames.
struct StageTimes {
  double detect = 0, locate = 0, track = 0, orient = 0;
  double total = 0;      ///< sum of the stages (reading frames excluded)
  double max_total = 0;  ///< slowest frame
};

/// Smallest difference of two undirected axis angles, radians, in [0, pi/2].
double axis_angle_error(double a, double b);

/// Joins each frame's harvest message to the truth of that frame and accumulates the figures.
/// Frames are added in the run's order (target switches follow the target ids over time).
class Evaluator {
 public:
  /// `min_iou`: the overlap a target's box needs with a potato's visible box to be matched to it.
  explicit Evaluator(double min_iou = 0.3) : min_iou_(min_iou) {}
  /// One frame: what Pipeline::process returned and the truth of every potato in it (frame_truth).
  void add(const FrameResult& result, const std::vector<FrameTruth>& truth);
  Figures figures() const;

 private:
  struct Errors {  // per matched frame, mm or degrees
    std::vector<double> ex, ey, ez, el, ew, ea, ea_full, cx, cy, cz;
  };
  double min_iou_;
  Figures figures_;  // counts and rows; the error summaries are made by figures()
  Errors errors_;
  std::map<int, int> potato_of_target_;  // target id -> matched potato id
};

/// Scores `run` (Pipeline::process of each frame) against `truth` (frame_truth of
/// each frame). Throws Error when the counts differ.
Figures evaluate_potato_run(const std::vector<FrameResult>& run, const std::vector<std::vector<FrameTruth>>& truth,
                            double min_iou = 0.3);

/// Stage times of `run`.
StageTimes stage_times(const std::vector<FrameResult>& run);

struct SequenceEvaluation {
  Figures figures;
  StageTimes ms;
  std::vector<FrameResult> run;                ///< what the pipeline returned, per frame
  std::vector<std::vector<FrameTruth>> truth;  ///< per frame
};

/// Runs `pipeline` (reset first) over the simulated sequence `seq` (`cropsight simulate potato`:
/// colour, depth, labels, poses.csv, groundtruth.json) and scores it. Throws Error(file, ...) when
/// the sequence is unreadable or lacks the simulator's truth.
SequenceEvaluation evaluate_potato_sequence(Pipeline& pipeline, const std::filesystem::path& seq, double min_iou = 0.3);

}  // namespace cropsight::pipeline::potato
