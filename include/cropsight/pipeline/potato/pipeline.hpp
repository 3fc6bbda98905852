#pragma once
// The potato harvesting pipeline ("Visual perception for autonomous harvesting of root
// vegetables growing in aeroponics", EPFL GrowBotHub): a RealSense D415 on the gripper, one potato
// harvested at a time. process() answers, every frame, the paper's questions in its order:
//   1. detect:     boxes of potatoes (Detector2D: classical or ONNX, chosen by the preset);
//   2. locate:     each box's 3D position and metric size from the depth (§3.5.1);
//   3. ripeness:   box area at the potato's depth >= ripeness_threshold_m2 (§3.4);
//   4. select / track: the nearest ripe potato, kept across frames, bridged by a visual tracker
//                  when detection misses it (§3.4, Fig. 3.7-3.8);
//   5. orient:     the target's length axis by segmentation + PCA / ellipse (§3.5.2);
//   6. message:    the harvest message of Table 3.2.
// No ground truth and no file writing here (pipeline/potato/eval.hpp evaluates a run).
// Not thread-safe: one pipeline per camera.
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cropsight/core/box_fusion.hpp"
#include "cropsight/core/config.hpp"
#include "cropsight/core/detection2d.hpp"
#include "cropsight/core/rgbd_frame.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/measure/orientation.hpp"
#include "cropsight/measure/position.hpp"
#include "cropsight/nn/onnx_detector.hpp"
#include "cropsight/pipeline/potato/config.hpp"
#include "cropsight/pipeline/potato/frame_result.hpp"
#include "cropsight/tracking/target_tracker.hpp"

namespace cropsight::pipeline::potato {

/// The 2D detector a preset's detector block names. Throws Error(where, ...).
std::unique_ptr<Detector2D> make_detector(const DetectorConfig& cfg, const std::string& where);

class Pipeline {
 public:
  /// Validates `cfg` and builds the detector it names. Throws Error(where, ...).
  explicit Pipeline(Config cfg, const std::string& where = "potato config");
  /// Replaces the preset's detector (tests, or a detector the caller built).
  Pipeline(Config cfg, std::unique_ptr<Detector2D> detector, const std::string& where = "potato config");
  ~Pipeline();

  /// One frame: colour (required) registered to depth (optional; metres = value * depth_scale).
  FrameResult process(const RgbdFrame& frame);
  /// Steps 1 and (with `orient_boxes`) 5 on a single image, not a sequence: no tracking, no
  /// target (detect potato). `depth_m` (metres) may be empty.
  ImageResult detect_image(const ColorImage& image, const Image<float>& depth_m, bool orient_boxes);
  /// The detector's class names (Detection2D::class_id indexes them).
  std::vector<std::string> detector_class_names() const;
  /// Step 5 alone on one box: the colourised depth when orientation.input = depth and `depth_m`
  /// (metres) is not empty, else the colour image (detect potato's overlays).
  measure::OrientationResult orient(const ColorImage& color, const Image<float>& depth_m, const Detection2D& box) const;
  /// Starts a new approach: drops the target.
  void reset();
  const Config& config() const { return cfg_; }

 private:
  std::vector<tracking::TargetCandidate> candidates(const FrameResult& r) const;
  void orient_target(const RgbdFrame& frame, const Image<float>& depth_m, FrameResult& r);

  Config cfg_;
  std::unique_ptr<Detector2D> detector_;
  tracking::TargetTracker tracker_;
};

}  // namespace cropsight::pipeline::potato
