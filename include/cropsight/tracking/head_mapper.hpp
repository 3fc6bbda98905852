#pragma once
// HeadMapper: what a detector's caller needs to size and map broccoli heads over a sequence.
// Per frame it measures every detection (measure::HeadSizer on the detection's points), writes
// the size into Detection::size_m, hands the detections to the TemporalFilter and writes the head
// id into Detection::track_id. After finish() it can say which tracks made it into the map, which
// gives the "temporally filtered" detection scores used for ap50 with the filter:
//
//   filtered_score(d) = d.score + confirmed_bonus  when d's head is in the map,
//                       d.score                    otherwise,
//
// with confirmed_bonus larger than any score spread, so detections of confirmed heads rank before
// every unconfirmed one (a detection is never removed: ranking it last is never worse for AP than
// dropping it). That score knows the whole pass (offline: ap50_offline). online_score(d) uses
// instead whether the head was confirmed at d's own frame (online: ap50_online, what a harvester
// acting live gets).
//
// It can also predict the heads a frame missed (tracking.predict_missed, an extension): for each
// head in T that the frame did not detect, the frame's points within predict_radius_scale × the
// head's radius of where the filter expects the head's centre. The filter keeps a head in T for
// max_missed_frames frames, and a head it has tracked is most often missed when it leaves the view
// (a sliver at the border, below the segmentation's minimum size) or hides under a leaf; the ball
// finds its remaining points. Predicted sets rank after the confirmed detections in ap50_temporal
// (predicted_score) and are written by `detect broccoli --track`; they never update the filter.
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "cropsight/core/config.hpp"
#include "cropsight/core/detection.hpp"
#include "cropsight/measure/head_size.hpp"
#include "cropsight/tracking/temporal_filter.hpp"

namespace cropsight {
struct OrganizedCloud;
struct CameraIntrinsics;
}  // namespace cropsight

namespace cropsight::tracking {

/// The sizing and tracking config of a broccoli preset: keys "sizing.*" and "tracking.*".
struct HeadMapperConfig {
  measure::HeadSizeConfig sizing;
  TemporalFilterConfig tracking;
  template <class V>
  void visit(V& v) {
    v("sizing", sizing, "head sizing (Kusumam §4.4)");
    v("tracking", tracking, "temporal filter (Kusumam §4.5)");
  }
  /// Applies only the "sizing." and "tracking." keys of `values` (other keys belong to other
  /// stages of the preset and are left alone).
  void apply(const ConfigMap& values, const std::string& where);
};

/// One measured detection, kept for per-frame size metrics and filtered scores.
struct MeasuredDetection {
  int frame = 0;
  int index = 0;  ///< index in that frame's detection list
  int track_id = -1;
  float score = 0.0f;
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();  ///< camera frame
  Eigen::Vector3d field_position = Eigen::Vector3d::Zero();
  measure::HeadSize size;  ///< invalid for partial detections (not measured)
  bool partial = false;    ///< box within tracking.border_margin_px of the image border
  /// Its head was confirmed at this frame (TemporalFilter::confirmed_now): what a robot acting
  /// live knows, unlike confirmed()/filtered_score(), which know the whole pass.
  bool confirmed_online = false;
};

class HeadMapper {
 public:
  explicit HeadMapper(const HeadMapperConfig& cfg = {});

  /// Sizes and tracks the detections of one frame (frames in increasing order). `cloud` is the
  /// frame's organised cloud the detection indices refer to.
  FrameAssociation add_frame(int frame, const OrganizedCloud& cloud, std::vector<Detection>& detections,
                             const std::optional<Eigen::Vector3d>& camera_position = std::nullopt);
  /// After add_frame(frame, cloud, ...): the heads of T that this frame did not detect, with their
  /// points in `cloud` (empty when tracking.predict_missed is false). `camera`: the intrinsics
  /// `cloud` was deprojected with (to bound the pixels searched). Does not change the filter.
  std::vector<PredictedHead> predict_missed(const OrganizedCloud& cloud, const CameraIntrinsics& camera) const;
  /// Ends the pass; returns the map (see TemporalFilter::finish).
  const std::vector<TrackedHead>& finish();

  const std::vector<TrackedHead>& map() const { return map_; }
  /// Every detection add_frame() measured, for per-frame size metrics and the filtered scores
  /// (empty when recording is off).
  const std::vector<MeasuredDetection>& detections() const { return measured_; }
  /// Whether add_frame() keeps a MeasuredDetection per detection (default on). A live consumer
  /// that never asks for offline scores (the ROS node) turns it off, so that memory does not
  /// grow with the frames (112 bytes a detection); the map and the filter are unchanged.
  void set_record_detections(bool on) { record_ = on; }
  bool confirmed(int track_id) const { return confirmed_.count(track_id) > 0; }
  /// Score of a recorded detection after the temporal filter (valid after finish()).
  float filtered_score(const MeasuredDetection& d) const;
  /// Rank score of a predicted set of head `track_id` (after finish()): after every confirmed
  /// detection (kConfirmedBonus − 1) when the head is in the map; otherwise nullopt (not a detection).
  std::optional<float> predicted_score(int track_id) const;
  /// The same two scores as a robot acting at the detection's frame has them (no hindsight): the
  /// bonus when the head was confirmed at that frame (MeasuredDetection::confirmed_online).
  static float online_score(const MeasuredDetection& d);
  static std::optional<float> online_predicted_score(const PredictedHead& p);
  const measure::HeadSizer& sizer() const { return sizer_; }
  const TemporalFilter& filter() const { return filter_; }

  static constexpr float kConfirmedBonus = 1e6f;

 private:
  measure::HeadSizer sizer_;
  TemporalFilter filter_;
  std::vector<MeasuredDetection> measured_;
  std::vector<TrackedHead> map_;
  std::set<int> confirmed_;
  std::vector<float> depth_scratch_;   // top_centroid's depths, reused across detections
  std::vector<float> select_scratch_;  // top_centroid's order-statistic bucket, reused
  bool finished_ = false;
  bool record_ = true;
};

}  // namespace cropsight::tracking
