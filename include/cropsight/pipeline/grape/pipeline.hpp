#pragma once
// The grape pipeline from the camera (Luo et al.), one class and one config:
// bunch and peduncle boxes (a 2D detector, or boxes given) → ROI per bunch (Eq. 1, overlapping
// ROIs merged) → coloured ROI cloud (Algorithm 1) → KNN-PCA normals → the grape segmenter →
// per bunch a labelled cloud in metres and a cut point on its peduncle.
// Pixels: x = column, y = row, origin top-left. Points: camera frame (x right, y down, z forward),
// metres.
#include <Eigen/Core>
#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cropsight/core/cloud.hpp"
#include "cropsight/core/config.hpp"
#include "cropsight/core/detection2d.hpp"
#include "cropsight/core/geometry_types.hpp"
#include "cropsight/core/rgbd_frame.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/pipeline/grape/config.hpp"
#include "cropsight/pipeline/grape/frame_result.hpp"
#include "cropsight/pipeline/grape/roi.hpp"
#include "cropsight/pipeline/grape/segmenter.hpp"

namespace cropsight::pipeline::grape {

/// Step 5 alone: the cut point of a labelled cloud (m). The points labelled
/// cfg.peduncle_label are clustered (Euclidean, cfg.cluster_tolerance); the largest cluster
/// gives the position (its centroid), the direction (its principal axis, sign chosen so that
/// it points up in the image: toward -y; an exactly horizontal axis points toward +x) and the
/// confidence (its point count). No peduncle point, or a largest cluster of fewer than
/// cfg.min_points points: std::nullopt (the bunch still has its labelled cloud). Ties between
/// clusters of one size go to the one with the smallest point index. Throws Error when the
/// cloud has no labels.
std::optional<CutPoint> grape_cut_point(const Cloud& cloud, const CutPointConfig& cfg = {});

/// The project's grape detector's boxes as GrapeDetections: category = class_id + 1 (class 0
/// grape → 1 bunch, class 1 peduncle → 2), as `detect objects` writes COCO category ids; the box
/// is the smallest pixel box covering the continuous one.
std::vector<Detection> grape_detections(const std::vector<Detection2D>& boxes);

class Pipeline {
 public:
  /// Validates `cfg` (Error(where, ...)). `detector` may be null when every call gives its boxes.
  Pipeline(Config cfg, Segmenter segmenter, std::unique_ptr<Detector2D> detector = nullptr,
           const std::string& where = "grape pipeline config");
  ~Pipeline();
  Pipeline(Pipeline&&) noexcept;
  Pipeline& operator=(Pipeline&&) noexcept;

  /// Every step on one frame (colour required, registered to depth), boxes from the detector.
  /// Throws Error when the pipeline has no detector, or as the boxes' overload.
  FrameResult process(const RgbdFrame& frame);
  /// Every step but the detection, on the boxes given. Throws Error for a frame without colour
  /// or whose colour, depth and camera sizes differ.
  FrameResult process(const RgbdFrame& frame, const std::vector<Detection>& detections) const;

  const Config& config() const { return cfg_; }
  const Segmenter& segmenter() const { return segmenter_; }
  bool has_detector() const { return detector_ != nullptr; }
  /// Nothing carries over from one frame to the next (each frame is judged alone); here so that
  /// every crop's pipeline has the same entry points.
  void reset() {}

 private:
  Config cfg_;
  Segmenter segmenter_;
  std::unique_ptr<Detector2D> detector_;
};

}  // namespace cropsight::pipeline::grape
