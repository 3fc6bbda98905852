#pragma once
// Which OpenCV tracker continues the potato target when detection misses it (§3.4: the
// paper's dlib correlation tracker is not in OpenCV). Measured on simulated approaches: from
// frames where the target potato is in full view, a tracker starts on the target's true visible
// box and is updated on the next `horizon` frames (the paper's TRACKING_LIM: how long the loop
// trusts it) with no detection; each update is scored against the target's true box. The cost
// that matters for a 30 fps loop is the frame on which tracking starts (init + first update) and
// each further update, in thread CPU time on one thread.
#include <filesystem>
#include <vector>

#include "cropsight/pipeline/potato/eval.hpp"
#include "cropsight/tracking/target_tracker.hpp"
#include "cropsight/tracking/visual_tracker.hpp"

namespace cropsight::pipeline::potato {

struct VisualTrackerTrialConfig {
  int horizon = 10;              ///< updates per trial (default: the paper's TRACKING_LIM)
  int stride = 3;                ///< frames between trial starts
  double success_iou = 0.5;      ///< an update succeeds at IoU >= this with the true box
  int min_visible_pixels = 400;  ///< a start (and a scored update) needs this much of the potato
  tracking::CsrtParams csrt = tracking::TargetTrackerConfig{}.csrt;  ///< CSRT's settings (the loop's default)
};

struct VisualTrackerEvaluation {
  tracking::VisualTrackerKind kind = tracking::VisualTrackerKind::csrt;
  int trials = 0;
  int updates = 0;              ///< updates scored (target visible with >= min_visible_pixels)
  int gave_up = 0;              ///< ... where the tracker had reported a loss (counts as IoU 0)
  int update_calls = 0;         ///< updates timed (a tracker that reported a loss is not updated again)
  double mean_iou = 0;          ///< over scored updates
  double success_rate = 0;      ///< fraction of scored updates with IoU >= success_iou
  double end_success_rate = 0;  ///< fraction of trials whose last scored update succeeded
  double first_init_ms = 0;     ///< the first init of this kind in the process (one-time set-up included)
  double init_ms = 0;           ///< mean init (trials after the first), thread CPU ms
  double init_ms_max = 0;
  double update_ms = 0;  ///< mean update, thread CPU ms
  double update_ms_max = 0;
};

/// Runs the trials of `config` with a tracker of `kind` over `sequences`, on one OpenCV thread.
/// Throws Error when kind is none or no trial could start.
VisualTrackerEvaluation evaluate_visual_tracker(tracking::VisualTrackerKind kind,
                                                const std::vector<TruthSequence>& sequences,
                                                const VisualTrackerTrialConfig& config = {});

}  // namespace cropsight::pipeline::potato
