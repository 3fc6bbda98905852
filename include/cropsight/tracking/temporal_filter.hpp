#pragma once
// The temporal filter of Kusumam et al. §4.5: follows broccoli heads across the frames of a pass
// along a row and builds a field map (one entry per head, position in the field frame, averaged
// size) without odometry.
//
// State: the camera position x_c and velocity v_c (field frame, metres and metres per frame), and
// three sets of heads: T (tracked), D (detected in the current frame), M (mapped).
// Every frame:
//   1. predict x_c ← x_c + v_c and move the detections D to the field frame with it;
//   2. (extension, on by default: motion_search) if the prediction left no detection within the
//      association radius of a tracked head, look for the camera shift that explains the most
//      detection–head pairs (translation voting over all pairs within motion_search_radius_m);
//   3. associate each detection with the nearest tracked head within association_radius_m
//      (one-to-one, closest pairs first, so two heads closer than the radius stay two heads);
//   4. correct x_c by the mean displacement of the associated pairs and set v_c to the change of
//      x_c since the previous frame (with use_poses, x_c comes from poses.csv instead);
//   5. raise the tracking score of associated heads and update their position and size by running
//      average; unassociated detections become new heads in T;
//   6. heads undetected for max_missed_frames frames move from T to M.
// At the end T moves to M and heads whose score is below min_track_score are dropped. Extension: a
// head seen in the recording's first or last frame had frames the recording never showed (it was
// leaving or entering the view), so it needs only edge_track_score (default 2) instead, or, when
// it was in view too briefly to be detected twice, detections whose mean classifier score reaches
// edge_single_detection_score (default 1.0).
// Extension (merge_radius_m, default 0.05 m): before the threshold, a head whose track began after
// another one's ended, within merge_radius_m of it, when that one reached min_track_score on its
// own, is the same head lost for max_missed_frames frames and found again (a leaf hid it, the
// classifier missed it): the two merge into one entry (scores add up, positions and sizes average
// over their frames), so the map holds no duplicate. Fragments that are each below the threshold
// are not merged (they would add up recurring false positives), and tracks that overlap in time
// never are: two heads closer than the radius stay two heads.
//
// Partial detections (extension): a head cut by the image border has its centroid off the head's
// centre by up to its radius, which breaks the 5 cm association and drags the camera estimate.
// Detections flagged `partial` therefore take part in none of the steps above. Afterwards (with
// partial_tracks, the default) each one is matched to the nearest head within
// partial_association_radius_m that no detection of this frame claimed: it raises that head's
// score and keeps it alive, but moves its position only while the head has no whole detection
// yet; an unmatched partial detection starts a head. A head seen only cut by the border (at the
// start or end of a pass, or at the edge of the view) can thus reach the map, placed at the mean
// of its partial centroids; the first whole detection resets the position to its own, and heads
// without whole detections never take part in the camera correction. Without partial_tracks a
// partial detection only takes the id of the nearest tracked head (no update).
//
// When the first frame carries a camera position (poses.csv) and anchor_first_pose is set, x_c
// starts there so that the map is in the same field frame as the ground truth; otherwise the
// field frame's origin is the camera position at the first frame. Positions of heads are the
// centroids of their visible points (the top of the head), not the centre of the plant.
#include <Eigen/Core>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cropsight/core/config.hpp"
#include "cropsight/measure/head_size.hpp"
#include "cropsight/tracking/field_transform.hpp"
#include "cropsight/tracking/track_results.hpp"

namespace cropsight::tracking {

struct TemporalFilterConfig {
  double association_radius_m = 0.05;
  int max_missed_frames = 3;
  double initial_score = 1.0;
  double score_increment = 1.0;
  double min_track_score = 3.0;
  double edge_track_score = 2.0;
  double edge_single_detection_score = 1.0;
  double min_detection_score = -1e30;
  bool use_poses = false;
  bool anchor_first_pose = true;
  bool motion_search = true;
  double motion_search_radius_m = 0.30;
  int motion_search_min_pairs = 2;
  bool startup_constant_velocity = true;
  std::vector<double> initial_velocity = {0.0, 0.0, 0.0};
  std::string camera_to_field = "y,x,-z";
  int border_margin_px = 2;
  double partial_association_radius_m = 0.10;
  bool partial_tracks = true;
  double position_cap_m = 0.02;
  double merge_radius_m = 0.05;
  bool merge_in_plane = true;
  double overlap_suppression = 0.75;
  bool predict_missed = true;
  double predict_radius_scale = 1.3;
  int predict_min_points = 10;

  // Long on purpose: every key of the temporal filter declared with its unit, range and source.
  template <class V>
  void visit(V& v) {
    v("association_radius_m", association_radius_m,
      "m; a detection joins the nearest tracked head within this distance (paper: 0.05 m, Kusumam §4.5)",
      Range::above(0));
    v("max_missed_frames", max_missed_frames,
      "frames; a head undetected this many frames in a row leaves T for the map M (paper: 3, §4.5)",
      Range::at_least(1));
    v("initial_score", initial_score, "1; tracking score of a new head (paper: score per detection; 1)", Range{});
    v("score_increment", score_increment, "1; score added per associated detection (paper: 1)", Range{});
    v("min_track_score", min_track_score,
      "1; heads whose final score is below this are dropped from the map (paper: threshold, value not given; 3 "
      "= seen in 3 frames)",
      Range{});
    v("edge_track_score", edge_track_score,
      "1; the threshold for heads seen in the sequence's first or last frame, whose track the recording cut "
      "(extension, never above min_track_score; < 0: min_track_score, the paper's single threshold)",
      Range{});
    v("edge_single_detection_score", edge_single_detection_score,
      "classifier score; a head whose track the recording cut enters the map below edge_track_score (e.g. "
      "detected once) when its detections' mean score is at least this (extension, 1.0 chosen on validation "
      "passes, docs/pipelines/broccoli-heads.md; 1e30: never, the rule before 2026-12-06)",
      Range{});
    v("min_detection_score", min_detection_score,
      "classifier score; detections below it are ignored by the tracker (default: keep all)", Range{});
    v("use_poses", use_poses, "bool; take x_c from poses.csv instead of estimating it (paper: no odometry, false)");
    v("anchor_first_pose", anchor_first_pose,
      "bool; start x_c at the first frame's pose when there is one, so the map shares the truth's field frame");
    v("motion_search", motion_search,
      "bool; when the predicted camera motion associates nothing, vote for the shift that does (extension)");
    v("motion_search_radius_m", motion_search_radius_m, "m; largest camera shift per frame the vote considers",
      Range::at_least(0));
    v("motion_search_min_pairs", motion_search_min_pairs,
      "pairs; once the camera velocity has been estimated, a voted shift must explain at least this many "
      "detection-head pairs (one false detection can always be paired with some head; 1 = any vote, as before)",
      Range::at_least(1));
    v("startup_constant_velocity", startup_constant_velocity,
      "bool; the first association after the start sets the velocity from the frames since each head was "
      "placed and re-places the heads placed meanwhile, as a constant velocity from the first frame implies "
      "(extension; false: from the last frame only, and heads placed before it keep the camera that did not move)");
    v("initial_velocity", initial_velocity, "m/frame, field frame [x, y, z]; v_c before the first estimate (0)");
    v("camera_to_field", camera_to_field,
      "axes; field X,Y,Z as signed camera axes (camera looks straight down; simulator: y,x,-z)");
    v("border_margin_px", border_margin_px,
      "px; a detection whose box comes this close to the image border is partial: it is neither sized nor used "
      "to move heads or the camera (extension; -1 = off, every detection is whole as in the paper)",
      Range::at_least(-1));
    v("partial_association_radius_m", partial_association_radius_m,
      "m; a partial detection takes the id of the nearest tracked head within this distance (its centroid is "
      "off-centre) so that it is credited to that head",
      Range::at_least(0));
    v("partial_tracks", partial_tracks,
      "bool; partial detections raise the score of (and start) heads, without moving the camera or a head that "
      "has whole detections (extension; false = they only take the nearest head's id)");
    v("position_cap_m", position_cap_m,
      "m; a head's position is the centroid of its points within this depth of its top (HeadMapper; the 2nd "
      "percentile of depth is the top), which the viewing angle hardly moves, unlike the centroid of the whole "
      "visible cap that drifted the estimated camera by ~2.5 % of the travel (extension; 0 = centroid of all "
      "points as in the paper)",
      Range::at_least(0));
    v("merge_radius_m", merge_radius_m,
      "m; at the end, a head whose track started after another's ended within this distance of it is merged into "
      "it when that one reached min_track_score (the same head lost and found again; extension, default the "
      "association radius 0.05 m; 0 = off, the paper's map keeps both)",
      Range::at_least(0));
    v("merge_in_plane", merge_in_plane,
      "measure the merge distance in the field plane (x, y) instead of 3D: the height of a head seen only cut by "
      "the image border is off by up to its radius (extension, default on: on the validation passes it merged one "
      "more duplicate and cost no head; false = 3D)");
    v("overlap_suppression", overlap_suppression,
      "fraction; when > 0, a map head is dropped at the end when a map head with a higher score lies closer in the "
      "field plane than this times the mean of their two diameters (the known one when only one is known): two real "
      "heads cannot overlap seen from above, so the weaker is a leaf beside a head tracked as a second head "
      "(extension: on the validation passes with poses 0.75 and 1.0 gave uk map precision 0.881 -> 0.945, "
      "spain 0.909 -> 0.968, recall unchanged; 0 = off, the paper's map)",
      Range::at_least(0.0));
    v("predict_missed", predict_missed,
      "bool; a head in T that a frame did not detect gets a predicted point set in that frame: the frame's points "
      "in a ball around where the filter expects it (HeadMapper::predict_missed; used by ap50_temporal and written "
      "by detect --track; extension, the paper's filter only re-ranks detections; false = off)");
    v("predict_radius_scale", predict_radius_scale,
      "1; the ball's radius as a multiple of the head's radius (half its running bounding-box width; chosen on "
      "tuning seeds 101/103 uk, 102/104 spain: 1.3)",
      Range::above(0));
    v("predict_min_points", predict_min_points, "points; fewer points in the ball give no predicted set",
      Range::at_least(1));
  }
};

/// One head seen in one frame, as the detector hands it to the tracker.
struct HeadObservation {
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();  ///< metres, camera frame
  float score = 0.0f;                                  ///< classifier score
  measure::HeadSize size;                              ///< per-frame size (may be invalid)
  bool partial = false;  ///< cut by the image border: labelled with a head id, never updates state
};

class TemporalFilter {
 public:
  explicit TemporalFilter(const TemporalFilterConfig& cfg = {}, const measure::HeadSizer& sizer = measure::HeadSizer{});

  /// Processes frame `frame` (strictly increasing). `camera_position` (field frame) is used when
  /// use_poses is set (then it is required) and, with anchor_first_pose, on the first frame.
  FrameAssociation update(int frame, const std::vector<HeadObservation>& detections,
                          const std::optional<Eigen::Vector3d>& camera_position = std::nullopt);

  /// Moves T to M and returns the map: heads with score ≥ min_track_score (≥ edge_track_score for
  /// heads seen in the first or last frame), sorted by id.
  /// The filter can be finished once; update() afterwards throws.
  std::vector<TrackedHead> finish();

  /// After finish(): (absorbed id, kept id) for each track merged into an earlier one
  /// (merge_radius_m); detections labelled with an absorbed id belong to the kept head.
  const std::vector<std::pair<int, int>>& merged_ids() const { return merged_ids_; }

  /// Online confirmation (what a robot acting at the current frame knows): head `id` is in T and
  /// its score already reaches min_track_score, or edge_track_score when it was seen in the
  /// recording's first frame. finish() decides with hindsight (the last frame, merges); a head
  /// confirmed now is not always in the final map and the other way round.
  bool confirmed_now(int id) const;
  bool confirmed_now(const TrackedHead& h) const;

  /// Every head ever created (T ∪ M, before the score threshold), by id.
  std::vector<TrackedHead> all_heads() const;
  const std::vector<TrackedHead>& tracked() const { return tracked_; }
  const std::vector<TrackedHead>& mapped() const { return mapped_; }
  const Eigen::Vector3d& camera_position() const { return x_c_; }
  const Eigen::Vector3d& camera_velocity() const { return v_c_; }
  const FieldTransform& transform() const { return transform_; }
  const TemporalFilterConfig& config() const { return cfg_; }

 private:
  struct Step;  // one update()'s working state (temporal_filter.cpp)
  // The steps of update(), in order (numbers as in the comment at the top of this file).
  void predict_camera(const std::optional<Eigen::Vector3d>& camera_position, Step& s);   // 1.
  void place_detections(const std::vector<HeadObservation>& detections, Step& s) const;  // D in the field
  void associate_detections(Step& s) const;                                              // 2.-3.
  void correct_camera(Step& s);                                                          // 4.
  void update_heads(const std::vector<HeadObservation>& detections, Step& s);            // 5.
  void add_partial_detections(const std::vector<HeadObservation>& detections, Step& s);  // extension
  void retire_missed_heads(const Step& s);                                               // 6.
  void add_sample(TrackedHead& h, const Eigen::Vector3d& p, const HeadObservation& d) const;
  TrackedHead new_head(int frame, const Eigen::Vector3d& p);    ///< next id, initial score, at p
  void touch(TrackedHead& h, int frame) const;                  ///< seen this frame: score, last frame
  void merge_lost_and_found();                                  ///< mapped_: merge_radius_m (see above)
  void suppress_overlaps(std::vector<TrackedHead>& map) const;  ///< overlap_suppression (see the config)
  void absorb(TrackedHead& into, const TrackedHead& later) const;
  double edge_threshold() const;  ///< edge_track_score, never above min_track_score (< 0: min_track_score)
  bool passes_edge_rule(const TrackedHead& h) const;  ///< a cut track's rule: edge threshold, or one strong detection

  TemporalFilterConfig cfg_;
  measure::HeadSizer sizer_;
  FieldTransform transform_;
  Eigen::Vector3d x_c_ = Eigen::Vector3d::Zero(), v_c_ = Eigen::Vector3d::Zero();
  std::vector<TrackedHead> tracked_, mapped_;
  std::vector<std::pair<int, int>> merged_ids_;
  int first_frame_ = -1, last_frame_ = -1;
  int next_id_ = 1;
  bool started_ = false, finished_ = false;
  bool has_velocity_ = false;  // v_c_ has been estimated from associated pairs (or poses)
  // Until then (startup_constant_velocity): the first frame's camera, and where and with which
  // camera estimate each head was placed (a head is seen only once before the first association).
  struct Birth {
    int id = 0, frame = 0;
    Eigen::Vector3d camera = Eigen::Vector3d::Zero();
  };
  Eigen::Vector3d x_first_ = Eigen::Vector3d::Zero();
  std::vector<Birth> births_;
  void start_constant_velocity(Step& s);  ///< 4. at the first association (startup_constant_velocity)
};

}  // namespace cropsight::tracking
