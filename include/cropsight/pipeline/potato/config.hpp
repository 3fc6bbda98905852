#pragma once
// The potato pipeline's one configuration (configs/potato*.yaml, --set key=value), one block per
// step of pipeline.hpp: detector.*, position.*, ripeness.*, tracking.*, orientation.*.
#include <array>
#include <string>

#include "cropsight/core/box_fusion.hpp"
#include "cropsight/core/config.hpp"
#include "cropsight/measure/orientation.hpp"
#include "cropsight/measure/position.hpp"
#include "cropsight/nn/onnx_detector.hpp"
#include "cropsight/pipeline/potato/blob_detector.hpp"
#include "cropsight/tracking/target_tracker.hpp"

namespace cropsight::pipeline::potato {

enum class DetectorBackend { classical, onnx, cnn, fusion };
constexpr std::array<const char*, 4> config_names(DetectorBackend) { return {"classical", "onnx", "cnn", "fusion"}; }

/// The detector slot: which backend and each backend's settings (keys detector.*).
struct DetectorConfig {
  DetectorBackend backend = DetectorBackend::classical;
  BlobConfig classical;
  nn::OnnxDetectorConfig onnx;
  std::string cnn_model;   ///< the project's CenterNet: .onnx (OpenCV DNN) or .pt (libtorch)
  BoxFusionConfig fusion;  ///< backend fusion: the classical detector and cnn_model, boxes fused (core/box_fusion.hpp)

  template <class V>
  void visit(V& v) {
    v("backend", backend,
      "classical | onnx | cnn | fusion (classical and cnn_model, weighted boxes fusion); the 2D detector "
      "(paper: SSD300 MobileNet v2, 70 ms a frame)");
    v("classical", classical, "the classical colour/range blob detector (pipeline/potato/blob_detector.hpp)");
    v("onnx", onnx, "a user's ONNX detector run by OpenCV DNN (nn/onnx_detector.hpp)");
    v("cnn_model", cnn_model,
      "path; the project's CenterNet for backends cnn and fusion: .onnx (OpenCV DNN) or .pt (nn/center_onnx.hpp); in a "
      "preset, relative to the preset's folder");
    v("fusion", fusion, "backend fusion: how the two detectors' boxes are joined");
  }
};

/// The one configuration of the potato pipeline, filled from one preset (configs/potato.yaml).
struct Config {
  DetectorConfig detector;
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

/// The configuration of `preset` (a name under configs/, e.g. "potato", or a YAML path) with
/// `overrides` (--set) applied and validated. Throws Error(file or "--set", ...).
Config load_config(const std::string& preset, const ConfigMap& overrides = {});

}  // namespace cropsight::pipeline::potato
