#pragma once
// The broccoli report of a sequence without ground truth (a user's own recording): what the
// pipeline found frame by frame, the field map it adds up to, the sizes and the time it took. No
// metric: there is nothing to compare with. Use: per frame pipeline.process(frame), then
// add_frame(frame, result); after the pass finish(pipeline.finish(), ...). Not thread-safe.
#include <vector>

#include "cropsight/core/rgbd_frame.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/pipeline/broccoli/frame_result.hpp"
#include "cropsight/pipeline/broccoli/tracking_eval.hpp"
#include "cropsight/report/broccoli_report.hpp"

namespace cropsight::report {

class BroccoliRunRecorder {
 public:
  /// `overlay_frames`: the frames whose pictures the report shows (ascending).
  explicit BroccoliRunRecorder(std::vector<int> overlay_frames);

  /// After the pipeline (tracking on) returned `result` for `frame`.
  void add_frame(const RgbdFrame& frame, const pipeline::broccoli::FrameResult& result);

  /// The report's data once the pass is over: `map` is Pipeline::finish()'s field map, `stages` the
  /// detector's stage totals over the pass; `sequence`, `model` and `estimator` label the page.
  BroccoliReportData finish(const std::vector<tracking::TrackedHead>& map, std::vector<StageTimer::Stage> stages,
                            const std::string& sequence, const std::string& model, const std::string& estimator);

 private:
  std::vector<int> overlay_frames_;
  std::vector<pipeline::broccoli::PassMaterial::Overlay> overlays_;
  std::vector<std::vector<int>> overlay_tracks_;  // per overlay: the head id of each detection
  std::vector<int> detections_per_frame_;
  std::vector<std::pair<double, double>> camera_path_;
  double tracking_ms_ = 0.0;
  long detections_ = 0;
};

}  // namespace cropsight::report
