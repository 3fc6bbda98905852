#pragma once
// TrackingEvaluator: what sizing, the temporal filter and the field map achieve over
// labelled passes (Kusumam et al. 2017 §5), from a Pipeline's
// results joined to the passes' ground truth (label images and groundtruth.json).
//
// Two protocols, named in every figure:
//   online  — what a robot acting at frame t knows: a detection ranks as confirmed when its head
//             was confirmed at frame t (TemporalFilter::confirmed_now). A harvester acting live
//             gets this AP.
//   offline — after the whole pass: a detection ranks as confirmed when its head reached the map
//             (hindsight: later frames, the last-frame rule, merges). The field map, its sizes
//             and Kusumam's Fig. 11c are offline figures.
// "single frame" ranks by the classifier score alone (no filter).
//
// Use: begin_pass(truth, has_poses, name); per frame pipeline.process(frame) then
// add_frame(frame, pipeline); end_pass(pipeline); after the last pass figures().
// Not thread-safe.
#include <Eigen/Core>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cropsight/core/image.hpp"
#include "cropsight/core/rgbd_frame.hpp"
#include "cropsight/eval/detection_ap.hpp"
#include "cropsight/eval/size_metrics.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/measure/head_size.hpp"
#include "cropsight/pipeline/broccoli/pipeline.hpp"

namespace cropsight::pipeline::broccoli {

struct TrackingEvalOptions {
  /// A true head counts for map recall when some frame shows it with at least this many points.
  int map_min_points = 300;
  /// Fit the size bias correction (scale, offset) of both estimators on the evaluated data
  /// (use training passes: the fit is then a calibration, not a result).
  bool fit_size_bias = false;
  /// Frames of the FIRST pass whose pictures are kept for a report (PassMaterial::overlays).
  std::vector<int> overlay_frames;
};

/// Everything measured, pooled over the passes. NaN = undefined (no heads, no map frame).
struct TrackingFigures {
  long frames = 0;
  // The field map against the visible true heads (offline by nature).
  bool map_aligned = true;  ///< false: a pass had no poses.csv, so the map is not in the truth's frame
  double map_precision = 0, map_recall = 0, duplicate_rate = 0, count_error_rel = 0;
  int count_error = 0, map_heads = 0, map_true_heads = 0, map_matched = 0, map_min_visible_points = 0;
  /// Map heads at a true head that no frame showed with map_min_visible_points (an ignore region,
  /// as the detection AP's visible figures treat it), and the precision without them:
  /// map_matched / (map_heads − map_ignored). map_precision counts them as false heads.
  int map_ignored = 0;
  double map_precision_visible = 0;
  /// Mean distance in the field plane between matched map heads and their true heads, metres
  /// (pooled over the passes' matches; NaN without a match): how well the map places a head.
  double map_mean_distance_m = 0;
  // Sizes: per mapped head (offline) and per detection on a true head (per frame).
  std::string size_estimator;
  bool hull_computed = true;
  eval::SizeMetrics head_size, head_bbox_raw, head_hull_raw;
  eval::SizeMetrics frame_size, frame_bbox_raw, frame_hull_raw;
  // Detection AP over every labelled head, and with heads of fewer than
  // detection.visible_truth_points visible points as ignore regions (_visible).
  double ap50_single_frame = 0, ap50_online = 0, ap50_offline = 0;
  double map50_95_single_frame = 0, map50_95_online = 0, map50_95_offline = 0;
  double ap50_single_frame_visible = 0, ap50_online_visible = 0, ap50_offline_visible = 0;
  double tracking_ms_per_frame = 0;                    ///< steps 2-4 of the pipeline, wall clock
  std::optional<measure::BiasFit> bbox_fit, hull_fit;  ///< with fit_size_bias: per detection on a true head
  /// With fit_size_bias: per mapped head matched to a true head (its mean raw size over the pass:
  /// the quantity the field map reports); absent when fewer than two heads were mapped and sized.
  std::optional<measure::BiasFit> head_bbox_fit, head_hull_fit;
};

/// Plain values of the first pass for a report (report::broccoli_report_data draws them).
struct PassMaterial {
  std::string sequence;
  struct MapPoint {
    double x = 0, y = 0, diameter_mm = 0;
    bool matched = false;
  };
  std::vector<MapPoint> map_heads, true_heads;         ///< field frame, metres
  std::vector<std::pair<double, double>> camera_path;  ///< field x, y per frame (the filter's estimate)
  std::vector<std::pair<double, double>> head_sizes;   ///< (truth, estimate) mm per matched mapped head
  struct FrameError {
    double distance_m = 0;  ///< lateral distance of the detection's centroid from the optical axis
    double bbox_error_mm = 0, hull_error_mm = 0;
  };
  std::vector<FrameError> frame_errors;  ///< per detection on a true head, raw estimators
  struct Overlay {
    int frame = 0;
    DepthImage depth;
    double depth_scale = 0.001;
    LabelImage labels;
    std::vector<std::pair<std::vector<int>, bool>> detections;  ///< pixels, head in the map (offline)
    std::vector<std::vector<int>> predicted;                    ///< pixels of predicted heads that reached the map
  };
  std::vector<Overlay> overlays;
  /// Per frame, pooled over passes: truth sets and candidates ranked without / with the filter
  /// (offline), for precision-recall curves.
  std::vector<eval::ScoredFrame> single_frames, offline_frames;
};

class TrackingEvaluator {
 public:
  explicit TrackingEvaluator(TrackingEvalOptions options = {});

  /// Starts a pass. `truth`: its groundtruth.json; `has_poses`: it has poses.csv (the map can
  /// then be placed in the truth's field frame).
  void begin_pass(const io::GroundTruth& truth, bool has_poses, const std::string& name);
  /// After pipeline.process(frame) (tracking on); `frame` must carry labels.
  void add_frame(const RgbdFrame& frame, const Pipeline& pipeline);
  /// Ends the pass: pipeline.finish(), then the map and the offline scores.
  void end_pass(Pipeline& pipeline);

  /// The figures so far (complete after the last end_pass). Throws Error when fit_size_bias has
  /// too few sizes to fit.
  TrackingFigures figures() const;
  const PassMaterial& material() const { return material_; }

 private:
  struct Frame {
    int index = 0;
    eval::ScoredFrame scored;                        // truth sets, candidates by classifier score
    std::vector<bool> small;                         // per truth set: an ignore region (_visible)
    std::vector<int> cand_det;                       // per candidate: measured detection, or -1
    std::vector<tracking::PredictedHead> predicted;  // heads the frame missed
    int overlay = -1;                                // index into material_.overlays, or -1
    std::vector<int> overlay_tracks;                 // track id per overlay detection
  };
  void score_frames(const tracking::HeadMapper& mapper);
  void add_sizes(const tracking::HeadMapper& mapper);
  void add_map(const std::vector<tracking::TrackedHead>& map);
  void keep_overlays(const tracking::HeadMapper& mapper);

  TrackingEvalOptions opt_;
  const io::GroundTruth* truth_ = nullptr;
  bool has_poses_ = false;
  std::string name_;
  std::string estimator_;
  bool compute_hull_ = true, aligned_cfg_ = true;
  int visible_points_ = 300, min_truth_points_ = 0;
  std::vector<Frame> frames_;             // current pass
  std::map<int, int> visible_;            // current pass: head id → most points seen
  std::map<std::size_t, int> det_truth_;  // current pass: measured detection → head id
  PassMaterial material_;
  eval::DetectionApAccumulator ap_single_, ap_online_, ap_offline_;
  eval::DetectionApAccumulator ap_single_visible_, ap_online_visible_, ap_offline_visible_;
  std::vector<double> head_est_, head_bbox_, head_hull_, head_true_;
  std::vector<double> frame_bbox_, frame_hull_, frame_est_, frame_true_;
  int map_heads_ = 0, true_heads_ = 0, matched_ = 0, duplicates_ = 0, ignored_ = 0;
  double match_distance_sum_ = 0.0;  // metres, over every pass's matches
  double tracking_ms_ = 0.0;
  long frames_seen_ = 0;
  bool map_unaligned_ = false;
};

}  // namespace cropsight::pipeline::broccoli
