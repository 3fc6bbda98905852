#pragma once
// Sizing, temporal filter and field map for the broccoli sub-commands (issue 4):
//
//   cropsight detect broccoli ... --track [--map map.csv]   sizes + track ids per detection, map CSV
//   cropsight eval broccoli ... --track [--fit-size-bias]   map / size metrics, ap50 with the filter
//   cropsight report --data SEQ --model MODEL ...           the broccoli report sections
//
// Config keys "sizing.*" and "tracking.*" (tracking/head_mapper.hpp) come from the same preset and
// --set values as the detector's; take_tracking_keys() splits them off before the detector's
// config_for_model() sees the rest.
#include <CLI/CLI.hpp>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cropsight/core/config.hpp"
#include "cropsight/core/detection.hpp"
#include "cropsight/core/rgbd_frame.hpp"
#include "cropsight/eval/detection_ap.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/pipeline/broccoli_detector.hpp"
#include "cropsight/report/broccoli_report.hpp"
#include "cropsight/tracking/head_mapper.hpp"

namespace cropsight::cli {

struct TrackOptions {
  bool track = false;
  std::string map;             ///< detect: --map FILE
  bool fit_size_bias = false;  ///< eval: fit the size bias correction on the evaluated data
  int map_min_points = 300;    ///< eval: true heads count for the map when seen with this many points
};

/// --track and --map (detect) or --track and --fit-size-bias (eval).
void add_track_options(CLI::App* cmd, TrackOptions& o, bool detect);

/// Moves the "sizing." and "tracking." keys out of `all` into the returned map.
ConfigMap take_tracking_keys(ConfigMap& all);

/// report --model: runs the model's detector, sizing and temporal filter over the labelled
/// sequence `data` and appends the broccoli sections to `page` (overlays of `frames_shown` evenly
/// spaced frames). Returns the eval-style metrics JSON.
nlohmann::json add_broccoli_report(report::HtmlPage& page, const std::string& data, const std::string& model,
                                   ConfigMap config, int frames_shown, bool quiet);

/// Human-readable lines of the tracking figures of an eval JSON.
void print_tracking_summary(const nlohmann::json& j);

/// detect broccoli --track: one HeadMapper over the sequence.
class DetectTracking {
 public:
  DetectTracking(const TrackOptions& o, const ConfigMap& keys, const std::string& where);
  /// Sizes and tracks the frame's detections; adds "heads": [{id, track_id, diameter_mm, bbox_mm,
  /// hull_mm, harvestable}] (id = 1-based detection number), "predicted": [{track_id, points,
  /// centroid}] (heads the frame missed, tracking.predict_missed) and the camera estimate to `line`.
  void frame(const RgbdFrame& frame, const pipeline::BroccoliDetector& detector, std::vector<Detection>& dets,
             nlohmann::json& line);
  /// Ends the pass, writes --map (atomically) and adds map figures to `summary`.
  void finish(nlohmann::json& summary);

 private:
  TrackOptions o_;
  tracking::HeadMapper mapper_;
};

/// eval broccoli --track and report --model: everything measured over labelled sequences.
class EvalTracking {
 public:
  EvalTracking(const ConfigMap& keys, const pipeline::BroccoliDetectorConfig& detector_cfg, const std::string& where,
               std::vector<int> overlay_frames = {});
  void begin_sequence(const io::SequenceReader& reader);
  /// After the detector processed `frame` (BroccoliEvaluator::add_frame or detector.process).
  void frame(const RgbdFrame& frame, const pipeline::BroccoliDetector& detector);
  void end_sequence();

  /// Metrics to merge into the eval JSON (NaN → null); also completes report_data().
  nlohmann::json json(bool fit_size_bias);
  /// Report data (PR curves, map, sizes, overlays); complete after json().
  report::BroccoliReportData& report_data() { return data_; }
  /// True heads count for map recall when some frame shows them with at least this many points.
  void set_map_min_points(int n) { map_min_points_ = n; }

 private:
  struct Frame {
    int index = 0;
    report::PrFrame pr;
    std::vector<int> cand_det;  // per candidate: index into the mapper's measured detections, or -1
    bool overlay = false;       // overlay frames keep their picture until the tracks are confirmed
    ColorImage image;
    LabelImage labels;
    std::vector<std::pair<std::vector<int>, int>> det_pixels;  // detection pixels, track id
    std::vector<tracking::PredictedHead> predicted;            // heads the frame missed (predict_missed)
  };
  ConfigMap keys_;
  std::string where_;
  tracking::HeadMapperConfig cfg_;
  pipeline::BroccoliDetectorConfig det_cfg_;
  std::vector<int> overlay_frames_;
  std::optional<tracking::HeadMapper> mapper_;
  const io::SequenceReader* reader_ = nullptr;
  std::string sequence_;
  std::vector<Frame> frames_;  // current sequence
  report::BroccoliReportData data_;
  // Pooled over sequences:
  int map_heads_ = 0, true_heads_ = 0, matched_ = 0, duplicates_ = 0;
  std::vector<double> head_est_, head_bbox_, head_hull_, head_true_;
  std::vector<double> frame_bbox_, frame_hull_, frame_est_, frame_true_;
  std::map<int, int> visible_;            // current sequence: head id → most points seen
  std::map<std::size_t, int> det_truth_;  // current sequence: measured detection → head id
  eval::DetectionApAccumulator ap_single_, ap_tracked_;
  std::vector<report::PrFrame> pr_single_, pr_tracked_;
  double tracking_ms_ = 0.0;
  long frames_seen_ = 0;
  std::size_t overlay_pending_ = 0;
  bool map_unaligned_ = false;
  int map_min_points_ = 300;
};

}  // namespace cropsight::cli
