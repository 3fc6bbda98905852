#pragma once
// The broccoli sections of `cropsight report --data SEQ --model MODEL`, in the order
// the page shows them (the result first): overlays of a few frames with the
// detections, the field map with true and estimated heads (Kusumam et al. Fig. 17/18), estimated
// against true size (Fig. 15) and size error against the head's distance from the optical axis
// (Fig. 16), per-stage timing, the key figures, and precision–recall curves at IoU 0.50…0.95
// (Montes et al. Fig. 3). They are result sections: the sequence's own sections
// (sequence_page.hpp, the data part) follow them on the page.
// The data are plain values gathered by the caller (the CLI runs the detector and tracker); this
// module only computes curves and draws.
#include <string>
#include <utility>
#include <vector>

#include "cropsight/core/timer.hpp"
#include "cropsight/eval/detection_ap.hpp"
#include "cropsight/report/html_page.hpp"

namespace cropsight::report {

/// One frame for precision–recall: ground-truth point sets and scored detections (pixel indices).
using PrFrame = eval::ScoredFrame;

struct PrCurve {
  double iou = 0.5;
  std::vector<double> recall, precision;  ///< one point per ranked detection
  double ap = 0.0;                        ///< all-point interpolated area (same definition as eval/detection_ap.hpp)
};

/// Curves at each IoU threshold. Matching as eval::DetectionApAccumulator: per frame, detections
/// by decreasing score take the unmatched truth of highest IoU, correct when IoU ≥ t; then all
/// detections ranked by score.
std::vector<PrCurve> pr_curves(const std::vector<PrFrame>& frames, const std::vector<double>& thresholds);
/// 0.50, 0.55, …, 0.95.
std::vector<double> coco_thresholds();

struct BroccoliReportData {
  std::string sequence, model, estimator;
  long frames = 0;
  /// false: a sequence without ground truth (broccoli_run_data.hpp): no true heads, no PR curves,
  /// no size errors; the map heads are all drawn alike and sizes as a distribution.
  bool has_truth = true;
  std::vector<int> detections_per_frame;                     ///< accepted heads per frame (may be empty)
  std::vector<std::pair<std::string, std::string>> metrics;  ///< key figures, in order
  std::vector<PrCurve> pr_single, pr_tracked;                ///< without / with the temporal filter
  struct MapPoint {
    double x = 0, y = 0, diameter_mm = 0;
    bool matched = false;
  };
  std::vector<MapPoint> map_heads, true_heads;         ///< field frame, metres
  std::vector<std::pair<double, double>> camera_path;  ///< field x, y per frame
  struct SizePoint {
    double truth_mm = 0, estimate_mm = 0;
  };
  std::vector<SizePoint> head_sizes;  ///< per mapped head matched to a true head (chosen estimator)
  struct FrameError {
    double distance_m = 0;  ///< lateral distance of the detection's centroid from the optical axis
    double bbox_error_mm = 0, hull_error_mm = 0;
  };
  std::vector<FrameError> frame_errors;   ///< per detection on a true head, raw estimators
  std::vector<StageTimer::Stage> stages;  ///< totals over `frames`
  double tracking_ms = 0.0;               ///< total sizing + tracking time over `frames`
  std::vector<Figure> overlays;
};

/// Appends the broccoli sections to `page`, in its result part.
void add_broccoli_sections(HtmlPage& page, const BroccoliReportData& data);

}  // namespace cropsight::report
