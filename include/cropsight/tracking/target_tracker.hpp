#pragma once
// Selection and tracking of the one potato the arm harvests (the potato paper, §3.4,
// Fig. 3.7-3.8; the authors' vision_lib/track_object.py).
//
// Every frame the tracker gets the frame's candidates (detections with their distance to the
// camera and ripeness, from measure/position.hpp) and the colour image:
//  * selecting (no target): the nearest ripe candidate with usable depth becomes the target (new
//    id) -> detected; none -> selecting.
//  * with a target: a candidate "lies within epsilon" of the last target box's centre when both
//    |du| < epsilon and |dv| < epsilon (pixels, per axis, as the authors' code compares; the paper's
//    EPSILON = 300). 300 px per axis admits nearly every potato in a 640 x 480 view, so when the
//    target's own box is missing for a frame (a root across it, a detector miss) another potato
//    takes over. Ours also gates by the last box itself: the candidate must overlap the last box
//    (moved by its last motion, predict_motion) by min_overlap of the smaller of the two, and its
//    area be within max_area_ratio of the last box's; the camera moves a few pixels a frame, so the
//    target's next box passes and a neighbour (beside it, not on it) does not. With merge_parts,
//    the other detections lying mostly inside that box are parts of the target split by a root,
//    and the target's box is their union. Association `nearest` (paper) takes the
//    nearest passing candidate (smallest distance); `closest` (ours) the one whose centre is
//    closest to the last centre. Found -> detected (the tracking counter resets).
//  * none within epsilon: the visual tracker (initialised on the last detected box) continues ->
//    tracked, for at most tracking_limit consecutive frames (paper TRACKING_LIM = 10). The next
//    frame without a match, or a visual-tracker failure, is `lost`: the target is dropped
//    (reported once, no box) and selection runs again from the next frame.
// Not thread-safe; one tracker per camera.
#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "cropsight/core/config.hpp"
#include "cropsight/core/detection2d.hpp"
#include "cropsight/core/image.hpp"
#include "cropsight/tracking/target_state.hpp"
#include "cropsight/tracking/visual_tracker.hpp"

namespace cropsight::tracking {

enum class TargetAssociation { nearest, closest };
constexpr std::array<const char*, 2> config_names(TargetAssociation) { return {"nearest", "closest"}; }

struct TargetTrackerConfig {
  double epsilon_px = 300;      ///< paper EPSILON: per-axis proximity to the last target centre, pixels
  double min_overlap = 0.5;     ///< intersection with the (predicted) last box over the smaller area; 0 = off (paper)
  double max_area_ratio = 4.0;  ///< most area ratio to the last box (either way); 0 = off (paper)
  bool predict_motion = true;   ///< the gate's box is the last box moved by its last motion (ours)
  bool merge_parts = true;      ///< detections mostly inside that box are parts of the target (ours)
  int tracking_limit = 10;      ///< paper TRACKING_LIM: most consecutive frames tracked without detection
  TargetAssociation association = TargetAssociation::closest;
  VisualTrackerKind visual_tracker = VisualTrackerKind::csrt;
  CsrtParams csrt;  ///< OpenCV's defaults (a smaller template was measured and not taken: potatoes.md)

  template <class V>
  void visit(V& v) {
    v("epsilon_px", epsilon_px,
      "px; a detection continues the target when |du| and |dv| between box centres are both below this "
      "(paper EPSILON = 300, compared per axis in pixels in the authors' track_object.py)",
      Range::above(0.0));
    v("min_overlap", min_overlap,
      "fraction; a detection continues the target only when its intersection with the last box (moved by its last "
      "motion) is at least this of the smaller box's area (ours, 0 = off as in the paper)",
      Range::within(0.0, 1.0));
    v("max_area_ratio", max_area_ratio,
      "ratio; ... and its box area is within this factor of the last box's, either way (ours, 0 = off as in the "
      "paper)",
      Range::at_least(0.0));
    v("predict_motion", predict_motion,
      "bool; the gate and `closest` use the last box moved by its motion in the last frame (constant velocity, at "
      "most a quarter of the box; ours, false = the last box as in the paper)");
    v("merge_parts", merge_parts,
      "bool; the other detections lying mostly inside that box are parts of the target split by a root: the "
      "target's box is their union (ours, false as in the paper)");
    v("tracking_limit", tracking_limit,
      "frames; most consecutive frames the visual tracker carries the target without detection (paper "
      "TRACKING_LIM = 10)",
      Range::at_least(0));
    v("association", association,
      "nearest | closest; among detections within epsilon: the nearest to the camera (paper) or the one "
      "closest to the last target centre (ours)");
    v("visual_tracker", visual_tracker,
      "csrt | kcf | mil | none; OpenCV tracker in place of the paper's dlib correlation tracker (chosen by `cropsight "
      "eval potato-tracker`, docs/pipelines/potatoes.md)");
    v("csrt_template_size", csrt.template_size,
      "px; CSRT's template side (smaller is cheaper: 100 took about half the CPU of 200 a frame; OpenCV's default 200)",
      Range::at_least(16));
    v("csrt_scales", csrt.scales, "CSRT's scale-filter scales per frame (OpenCV's default 33)", Range::at_least(1));
    v("csrt_segmentation", csrt.segmentation,
      "bool; CSRT's colour-histogram mask of the filter (OpenCV's default true)");
    v("csrt_admm_iterations", csrt.admm_iterations, "CSRT's ADMM iterations per frame (OpenCV's default 4)",
      Range::at_least(1));
  }
};

/// One candidate of a frame.
struct TargetCandidate {
  Detection2D box;
  float distance_m = 0;  ///< distance used for "nearest" (the box centre's depth)
  bool ripe = false;     ///< measure::is_ripe
  bool depth_ok = false;
};

/// The tracker's answer for one frame.
struct TargetUpdate {
  TargetState state = TargetState::selecting;
  int target_id = 0;               ///< 1, 2, ... per selected target; 0 = none
  std::optional<Detection2D> box;  ///< the target's box (detected or tracked)
  int candidate = -1;              ///< index into the frame's candidates when detected, else -1
  int frames_tracked = 0;          ///< consecutive frames without detection so far
  int parts = 1;                   ///< detections merged into `box` (merge_parts); 1 = box is candidate's
  bool has_target() const { return box.has_value(); }
};

class TargetTracker {
 public:
  /// `visual` overrides the tracker made from cfg.visual_tracker (tests pass scripted ones).
  explicit TargetTracker(TargetTrackerConfig cfg = {}, std::unique_ptr<VisualTracker> visual = nullptr);
  ~TargetTracker();

  /// Advances one frame. `image` may be null (no visual tracking then).
  TargetUpdate update(const ColorImage* image, const std::vector<TargetCandidate>& candidates);
  /// Drops the target; the next update selects.
  void reset();
  const TargetTrackerConfig& config() const { return cfg_; }

 private:
  int select(const std::vector<TargetCandidate>& candidates) const;
  int associate(const std::vector<TargetCandidate>& candidates) const;
  TargetUpdate detected(const ColorImage* image, const std::vector<TargetCandidate>& candidates, int index, bool fresh);
  void move_to(const Detection2D& box, bool fresh);
  Detection2D predicted() const;
  bool in_gate(const Detection2D& box, const Detection2D& predicted) const;
  Detection2D merge_parts(const std::vector<TargetCandidate>& candidates, int index, int& parts) const;

  TargetTrackerConfig cfg_;
  std::unique_ptr<VisualTracker> visual_;
  bool has_target_ = false;
  int target_id_ = 0, next_id_ = 1, frames_tracked_ = 0;
  Detection2D last_box_;
  float vu_ = 0, vv_ = 0;  // the last box centre's motion per frame, pixels (predict_motion)
  // The visual tracker is initialised lazily, on the last detected frame, when a miss needs it:
  // detected frames (most of them) cost no tracker initialisation.
  ColorImage last_image_;
  bool visual_started_ = false, have_last_image_ = false;
};

}  // namespace cropsight::tracking
