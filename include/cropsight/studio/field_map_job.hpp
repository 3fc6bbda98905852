#pragma once
// The field map of the studio's sequence, for the page's map panel: one background thread runs the
// studio's model with tracking on (make_pipeline with track=true, as `cropsight detect broccoli
// --track --map` does) over every frame in order, and keeps the map the temporal filter makes at
// the end of the pass (tracking/temporal_filter.hpp) together with the frames whose detections
// joined each head, so that the page can draw the heads at their field positions, highlight those
// of the open frame and jump to a frame that shows a head. The page polls status() and may cancel().
//
// Positions are in the field frame (tracking.camera_to_field, metres). With poses.csv the map is
// anchored at the first camera pose; without it the filter estimates the camera's motion from the
// heads themselves (the paper's way: no odometry) and the origin is the camera at the first frame.
// A frame the pipeline cannot process fails the job with the pipeline's one-line message, which
// the page shows in place of the map.
//
// Thread-safe: every public call may come from any server thread.
#include <Eigen/Core>
#include <atomic>
#include <filesystem>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "cropsight/tracking/track_results.hpp"

namespace cropsight::studio {

struct MapHead {
  tracking::TrackedHead head;  ///< the map's entry (field frame, metres; diameter in mm)
  std::vector<int> frames;     ///< frames whose detections joined this head (merged tracks too), ascending
};

struct FieldMapStatus {
  std::string state = "idle";  ///< idle | running | done | failed | cancelled
  double progress = 0.0;       ///< 0..1 of the frames
  std::string message;         ///< why a job failed
  bool poses = false;          ///< the sequence has poses.csv (the map is anchored at its first pose)
  std::vector<MapHead> heads;  ///< the map (state done)
  /// The filter's camera position after each frame, field frame (m) (state done).
  std::vector<Eigen::Vector3d> camera;
  double seconds = 0.0;
};

class FieldMapJob {
 public:
  /// `model`: the studio's model (a shipped name or a file; "" = the default broccoli model).
  FieldMapJob(std::filesystem::path sequence, std::string model);
  /// Cancels a running job and waits for it.
  ~FieldMapJob();
  FieldMapJob(const FieldMapJob&) = delete;
  FieldMapJob& operator=(const FieldMapJob&) = delete;

  /// Starts building the map; false when a job is running.
  bool start();
  void cancel();
  FieldMapStatus status() const;

 private:
  void run();

  std::filesystem::path sequence_;
  std::string model_;
  mutable std::mutex mutex_;
  FieldMapStatus status_;
  std::atomic<bool> cancel_{false};
  std::thread thread_;
};

}  // namespace cropsight::studio
