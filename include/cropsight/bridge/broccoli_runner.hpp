#pragma once
// The broccoli pipeline (pipeline::broccoli::Pipeline) behind a C++17 header, for the ROS node: the
// pipeline's own headers are C++20, its results (frame_result.hpp, tracking/track_results.hpp) are
// plain C++17 data and come out as they are. One runner per camera; not thread-safe. Errors:
// cropsight::Error naming the file or input.
#include <memory>
#include <string>
#include <vector>

#include "cropsight/bridge/frame_buffers.hpp"
#include "cropsight/pipeline/broccoli/frame_result.hpp"
#include "cropsight/tracking/track_results.hpp"

namespace cropsight::bridge {

struct BroccoliRunnerOptions {
  std::string model;              ///< a shipped model's name or a model file (cropsight train broccoli)
  std::string preset;             ///< optional preset name or YAML path over the model's config
  std::vector<std::string> sets;  ///< optional "key=value" overrides (--set)
  bool track = true;              ///< size the heads and run the temporal filter (the field map)
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
  pipeline::broccoli::FrameResult process(const FrameBuffers& frame);
  /// The heads confirmed now (TemporalFilter::confirmed_now; online: what a robot knows at this
  /// frame, not the map finish() decides with hindsight), field frame. Empty without tracking.
  std::vector<tracking::TrackedHead> current_map() const;
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
