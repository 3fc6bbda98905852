#pragma once
// The potato pipeline (pipeline::potato::Pipeline) behind a C++17 header, for the ROS node.
// One runner per camera; not thread-safe. Errors: cropsight::Error naming the file or input.
#include <memory>
#include <string>
#include <vector>

#include "cropsight/bridge/frame_buffers.hpp"

namespace cropsight::bridge {

struct PotatoRunnerOptions {
  std::string preset = "potato";  ///< preset name (configs/) or YAML path
  std::vector<std::string> sets;  ///< "key=value" overrides (--set)
};

struct PotatoBox {
  float x1 = 0, y1 = 0, x2 = 0, y2 = 0;  ///< pixels
  int class_id = 0;
  float score = 0;
  bool ripe = false;
  float x = 0, y = 0, z = 0;  ///< m, camera frame (0 when the depth is not usable)
  bool depth_ok = false;
};

/// The harvest message (the paper's Table 3.2 and what `harvest potato` prints).
struct PotatoHarvest {
  int frame = 0;
  double timestamp = 0;
  bool detection = false, depth_ok = false;
  float x = 0, y = 0, z = 0;    ///< m, camera frame
  float height = 0, width = 0;  ///< m
  float angle = 0;              ///< rad, [0, pi), counter-clockwise from the image x axis
  bool angle_ok = false, cut = false;
  int target_id = 0;
  int state = 0;  ///< 0 selecting, 1 detected, 2 tracked, 3 lost (tracking::TargetState)
  float score = 0;
  PotatoBox box;  ///< the target's box (when detection)
};

struct PotatoFrameOut {
  std::vector<PotatoBox> detections;
  PotatoHarvest target;
  double ms_detect = 0, ms_locate = 0, ms_track = 0, ms_orient = 0;
};

class PotatoRunner {
 public:
  /// Loads and validates the preset. Throws Error(file or "--set", ...).
  explicit PotatoRunner(const PotatoRunnerOptions& options);
  ~PotatoRunner();
  PotatoRunner(const PotatoRunner&) = delete;
  PotatoRunner& operator=(const PotatoRunner&) = delete;

  /// One frame: colour required, depth optional (empty vector). Throws Error("frame N", ...) on
  /// a size mismatch.
  PotatoFrameOut process(const FrameBuffers& frame);
  /// Starts a new approach (drops the target).
  void reset();
  std::vector<std::string> class_names() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cropsight::bridge
