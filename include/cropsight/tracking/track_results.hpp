#pragma once
// What the temporal filter and the head mapper hand out per frame and per pass: the field map's
// heads, a frame's associations and the heads a frame missed. Plain data (Eigen and the standard
// library only) in C++17, so that callers built as C++17 (the ROS nodes) use these types as they
// are. Frames: the field frame of tracking.camera_to_field (metres) and the camera frame (x right,
// y down, z forward, metres).
#include <Eigen/Core>
#include <vector>

namespace cropsight::tracking {

/// A head of the filter's tracked set T or of its map M (TemporalFilter, temporal_filter.hpp).
struct TrackedHead {
  int id = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< field frame, metres (running average)
  double score = 0.0;                                  ///< tracking score
  int frames_seen = 0;                                 ///< associated detections (whole and partial)
  int partial_frames = 0;                              ///< of which partial (cut by the border)
  int whole_frames() const { return frames_seen - partial_frames; }
  int first_frame = 0, last_frame = 0;
  int missed = 0;                       ///< consecutive frames without a detection (T only)
  double mean_detection_score = 0.0;    ///< running average of the classifier scores
  int size_samples = 0;                 ///< frames with a valid size
  double bbox_mm = 0.0, hull_mm = 0.0;  ///< running averages of the raw estimators
  double diameter_mm = 0.0;             ///< corrected diameter of the chosen estimator
  bool harvestable = false;
};

/// What TemporalFilter::update did with each detection of the frame.
struct FrameAssociation {
  std::vector<int> track_ids;                                 ///< per input detection: head id, or -1 when ignored
  std::vector<bool> new_track;                                ///< per input detection: started a new head
  Eigen::Vector3d camera_position = Eigen::Vector3d::Zero();  ///< x_c after the update
  Eigen::Vector3d camera_velocity = Eigen::Vector3d::Zero();  ///< v_c after the update
  int associated = 0;
  bool motion_searched = false;
};

/// A tracked head the last frame did not detect, and its points in that frame
/// (HeadMapper::predict_missed, head_mapper.hpp).
struct PredictedHead {
  int track_id = -1;
  std::vector<int> indices;                            ///< pixel indices, ascending
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();  ///< of those points, camera frame (m)
  Eigen::Vector3f centre = Eigen::Vector3f::Zero();    ///< the ball's centre, camera frame (m)
  float radius_m = 0.0f;                               ///< the ball's radius (m)
  bool confirmed_online = false;                       ///< the head was confirmed at this frame
};

}  // namespace cropsight::tracking
