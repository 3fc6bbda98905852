#pragma once
// The potato harvesting pipeline (issue 22; "Visual perception for autonomous harvesting of root
// vegetables growing in aeroponics", EPFL GrowBotHub): a RealSense D415 on the gripper, one potato
// harvested at a time. process() answers, every frame, the paper's questions in its order:
//   1. detect:     boxes of potatoes (Detector2D: classical or ONNX, chosen by the preset);
//   2. locate:     each box's 3D position and metric size from the depth (§3.5.1);
//   3. ripeness:   box area at the potato's depth >= ripeness_threshold_m2 (§3.4);
//   4. select / track: the nearest ripe potato, kept across frames, bridged by a visual tracker
//                  when detection misses it (§3.4, Fig. 3.7-3.8);
//   5. orient:     the target's length axis by segmentation + PCA / ellipse (§3.5.2);
//   6. message:    the harvest message of Table 3.2.
// No ground truth and no file writing here (pipeline/potato/potato_eval.hpp evaluates a run).
// Not thread-safe: one pipeline per camera.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "cropsight/core/box_fusion.hpp"
#include "cropsight/core/config.hpp"
#include "cropsight/core/detection2d.hpp"
#include "cropsight/core/rgbd_frame.hpp"
#include "cropsight/measure/orientation.hpp"
#include "cropsight/measure/position.hpp"
#include "cropsight/nn/onnx_detector.hpp"
#include "cropsight/pipeline/potato/potato_blob_detector.hpp"
#include "cropsight/tracking/target_tracker.hpp"

namespace cropsight::pipeline::potato {

enum class DetectorBackend { classical, onnx, cnn, fusion };
constexpr std::array<const char*, 4> config_names(DetectorBackend) { return {"classical", "onnx", "cnn", "fusion"}; }

/// The detector slot: which backend and each backend's settings (keys detector.*).
struct PotatoDetectorConfig {
  DetectorBackend backend = DetectorBackend::classical;
  PotatoBlobConfig classical;
  nn::OnnxDetectorConfig onnx;
  std::string cnn_model;   ///< the project's CenterNet (issue 24): .onnx (OpenCV DNN) or .pt (libtorch)
  BoxFusionConfig fusion;  ///< backend fusion: the classical detector and cnn_model, boxes fused (core/box_fusion.hpp)

  template <class V>
  void visit(V& v) {
    v("backend", backend,
      "classical | onnx | cnn | fusion (classical and cnn_model, weighted boxes fusion); the 2D detector "
      "(paper: SSD300 MobileNet v2, 70 ms a frame)");
    v("classical", classical, "the classical colour/range blob detector (pipeline/potato/potato_blob_detector.hpp)");
    v("onnx", onnx, "a user's ONNX detector run by OpenCV DNN (nn/onnx_detector.hpp)");
    v("cnn_model", cnn_model,
      "path; the project's CenterNet for backends cnn and fusion: .onnx (OpenCV DNN) or .pt (nn/center_onnx.hpp); in a "
      "preset, relative to the preset's folder");
    v("fusion", fusion, "backend fusion: how the two detectors' boxes are joined");
  }
};

/// The one configuration of the potato pipeline, filled from one preset (configs/potato.yaml).
struct PotatoPipelineConfig {
  PotatoDetectorConfig detector;
  measure::PositionConfig position;
  measure::RipenessConfig ripeness;
  tracking::TargetTrackerConfig tracking;
  measure::OrientationConfig orientation;
  /// Depth span of the colourised depth image the orientation step segments when
  /// orientation.input = depth and the frame has metric depth only (the RealSense viewer's map).
  double colormap_near_m = 0.2, colormap_far_m = 1.0;

  template <class V>
  void visit(V& v) {
    v("detector", detector, "step 1: the 2D detector");
    v("position", position, "step 2: 3D position from the depth (paper §3.5.1)");
    v("ripeness", ripeness, "step 3: ripeness by metric box area (paper §3.4)");
    v("tracking", tracking, "step 4: target selection and tracking (paper §3.4)");
    v("orientation", orientation, "step 5: orientation by segmentation + axis (paper §3.5.2)");
    v("colormap_near_m", colormap_near_m, "m; near end (red) of the colourised depth for orientation.input = depth",
      Range::at_least(0));
    v("colormap_far_m", colormap_far_m, "m; far end (blue) of the colourised depth", Range::above(0));
  }
  /// Ranges and the rules between fields; throws Error(where, "'key' ...").
  void validate(const std::string& where) const;
};

/// The harvest message (paper Table 3.2: detection, depth_ok, x, y, z, height, width, angle) plus
/// what a controller or a log needs to follow it.
struct HarvestTarget {
  int frame = 0;
  double timestamp = 0;         ///< s, from the frame
  bool detection = false;       ///< a target is in view this frame (detected or tracked)
  bool depth_ok = false;        ///< its depth is usable (within range, enough valid pixels)
  float x = 0, y = 0, z = 0;    ///< m, camera frame (x right, y down, z forward)
  float height = 0, width = 0;  ///< m, box sides at the potato's depth
  float angle = 0;              ///< rad, length axis, counter-clockwise from the image x axis, [0, π)
  bool angle_ok = false;        ///< the orientation step found the potato in the box
  bool cut = false;             ///< the box touches the image border: x, y, z are of the visible part
  int target_id = 0;            ///< 1, 2, ... per selected target; 0 = none
  tracking::TargetState state = tracking::TargetState::selecting;
  float score = 0;  ///< detector score of the target's box (0 when tracked)
  Detection2D box;  ///< pixels
};

/// Everything one frame produced (the message and what led to it).
struct PotatoFrameResult {
  std::vector<Detection2D> detections;
  std::vector<measure::Position3D> positions;  ///< one per detection
  std::vector<bool> ripe;                      ///< one per detection
  HarvestTarget target;
  double ms_detect = 0, ms_locate = 0, ms_track = 0, ms_orient = 0;  ///< stage times
};

/// The 2D detector a preset's detector block names. Throws Error(where, ...).
std::unique_ptr<Detector2D> make_potato_detector(const PotatoDetectorConfig& cfg, const std::string& where);

class PotatoPipeline {
 public:
  /// Validates `cfg` and builds the detector it names. Throws Error(where, ...).
  explicit PotatoPipeline(PotatoPipelineConfig cfg, const std::string& where = "potato config");
  /// Replaces the preset's detector (tests, or a detector the caller built).
  PotatoPipeline(PotatoPipelineConfig cfg, std::unique_ptr<Detector2D> detector,
                 const std::string& where = "potato config");
  ~PotatoPipeline();

  /// One frame: colour (required) registered to depth (optional; metres = value * depth_scale).
  PotatoFrameResult process(const RgbdFrame& frame);
  /// Step 1 alone, for single images (detect potato). `depth_m` may be null or empty.
  std::vector<Detection2D> detect(const ColorImage& image, const Image<float>* depth_m = nullptr);
  /// The detector's class names (Detection2D::class_id indexes them).
  std::vector<std::string> detector_class_names() const;
  /// Step 5 alone on one box: the colourised depth when orientation.input = depth and `depth_m`
  /// (metres) is not empty, else the colour image (detect potato's overlays).
  measure::OrientationResult orient(const ColorImage& color, const Image<float>& depth_m, const Detection2D& box) const;
  /// Starts a new approach: drops the target.
  void reset();
  const PotatoPipelineConfig& config() const { return cfg_; }

 private:
  std::vector<tracking::TargetCandidate> candidates(const PotatoFrameResult& r) const;
  void orient_target(const RgbdFrame& frame, const Image<float>& depth_m, PotatoFrameResult& r);

  PotatoPipelineConfig cfg_;
  std::unique_ptr<Detector2D> detector_;
  tracking::TargetTracker tracker_;
};

/// The configuration of `preset` (a name under configs/, e.g. "potato", or a YAML path) with
/// `overrides` (--set) applied and validated. Throws Error(file or "--set", ...).
PotatoPipelineConfig load_potato_config(const std::string& preset, const ConfigMap& overrides = {});

}  // namespace cropsight::pipeline::potato
