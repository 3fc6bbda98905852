#pragma once
// The broccoli pipeline (pipeline::broccoli::Pipeline) behind a C++17 header, for the ROS node.
// One runner per camera; not thread-safe. Errors: cropsight::Error naming the file or input.
#include <memory>
#include <string>
#include <vector>

#include "cropsight/bridge/frame_buffers.hpp"

namespace cropsight::bridge {

struct BroccoliRunnerOptions {
  std::string model;              ///< a shipped model's name or a model file (cropsight train broccoli)
  std::string preset;             ///< optional preset name or YAML path over the model's config
  std::vector<std::string> sets;  ///< optional "key=value" overrides (--set)
  bool track = true;              ///< size the heads and run the temporal filter (the field map)
};

/// One head of one frame, as `detect broccoli` writes it.
struct BroccoliHead {
  int id = 0;                                        ///< 1-based rank in the frame (best score first)
  float score = 0;                                   ///< classifier score
  float x = 0, y = 0, z = 0;                         ///< centroid, m, camera frame
  float box_x = 0, box_y = 0, box_w = 0, box_h = 0;  ///< pixels
  int points = 0;                                    ///< the head's points in the organised cloud
  float size_m = 0;   ///< diameter, m (tracking; 0 = not measured, e.g. cut by the border)
  int track_id = -1;  ///< field-map head id (tracking; -1 = none)
};

struct BroccoliFrameOut {
  int frame = 0;
  std::vector<BroccoliHead> heads;
  double detect_ms = 0, track_ms = 0;  ///< wall clock of detection and of sizing + tracking
};

/// One head of the field map (the CSV of `detect broccoli --track --map`).
struct BroccoliMapHead {
  int id = 0;
  double x = 0, y = 0, z = 0;  ///< field frame, m
  double diameter_mm = 0;
  int frames_seen = 0;
  bool harvestable = false;
};

class BroccoliRunner {
 public:
  /// Loads the model and the config (model's ← preset ← sets). Throws Error(file or "--set", ...).
  explicit BroccoliRunner(const BroccoliRunnerOptions& options);
  ~BroccoliRunner();
  BroccoliRunner(const BroccoliRunner&) = delete;
  BroccoliRunner& operator=(const BroccoliRunner&) = delete;

  /// The next frame of the pass (increasing order). Throws Error("frame N", ...) when the depth
  /// size does not match the camera or a camera value is out of range.
  BroccoliFrameOut process(const FrameBuffers& frame);
  /// The heads confirmed now (TemporalFilter::confirmed_now; online: what a robot knows at this
  /// frame, not the map finish() decides with hindsight). Empty without tracking.
  std::vector<BroccoliMapHead> current_map() const;
  /// Ends the pass, writes the field map CSV atomically (tracking::write_field_map) and starts
  /// a new pass. Throws Error when tracking is off or the file cannot be written.
  void finish_and_write_map(const std::string& csv_path);
  bool tracking() const;
  /// The pipeline variant the model was trained for ("oes", "org", "fec").
  std::string pipeline_name() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cropsight::bridge
