#pragma once
// The grape pipeline from the camera (Luo et al., issue 24 item 3), one class and one config:
// bunch and peduncle boxes (a 2D detector, or boxes given) → ROI per bunch (Eq. 1, overlapping
// ROIs merged) → coloured ROI cloud (Algorithm 1) → KNN-PCA normals → the grape segmenter →
// per bunch a labelled cloud in metres and a cut point on its peduncle.
// Pixels: x = column, y = row, origin top-left. Points: camera frame (x right, y down, z forward),
// metres.
#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cropsight/core/cloud.hpp"
#include "cropsight/core/config.hpp"
#include "cropsight/core/detection2d.hpp"
#include "cropsight/core/geometry_types.hpp"
#include "cropsight/core/rgbd_frame.hpp"
#include "cropsight/pipeline/grape/grape_roi.hpp"
#include "cropsight/pipeline/grape/grape_segmenter.hpp"

namespace cropsight::pipeline {

/// Where to cut a bunch: on its peduncle, found as the largest Euclidean cluster of the points
/// the segmenter labels peduncle.
struct GrapeCutPointConfig {
  int peduncle_label = 2;           ///< segmenter label of peduncle points (the dataset's label 2)
  double cluster_tolerance = 0.01;  ///< m; peduncle points closer than this join one cluster (ours)
  int min_points = 10;              ///< points; a largest cluster with fewer gives no cut point (ours)

  template <class V>
  void visit(V& v) {
    v("peduncle_label", peduncle_label, "id; segmenter label of peduncle points (dataset: 2)", Range::at_least(0));
    v("cluster_tolerance", cluster_tolerance,
      "m; peduncle points closer than this join one Euclidean cluster (ours: 0.01)", Range::above(0));
    v("min_points", min_points,
      "points; a largest peduncle cluster with fewer gives no cut point (ours: 10; PCA needs 3)",
      Range::at_least(3, "a principal direction needs three points"));
  }
};

/// The whole pipeline's config (configs/grape-camera.yaml). The segmenter has its own
/// (GrapeSegmenterConfig, configs/grape-best.yaml): it is built once and handed to the pipeline.
struct GrapePipelineConfig {
  GrapeRoiConfig roi;
  GrapeCutPointConfig cut_point;

  template <class V>
  void visit(V& v) {
    v("roi", roi, "steps 1-3: ROI from the boxes (Eq. 1), its coloured cloud (Algorithm 1) and normals");
    v("cut_point", cut_point, "step 5: the cut point on the labelled peduncle");
  }
  /// Throws Error(where, ...) naming the first key out of range (roi.validate's rules included).
  void validate(const std::string& where) const;
};

/// A cut point on a bunch's peduncle, camera frame.
struct GrapeCutPoint {
  Eigen::Vector3f position = Eigen::Vector3f::Zero();    ///< m: centroid of the peduncle cluster
  Eigen::Vector3f direction = Eigen::Vector3f::UnitY();  ///< unit principal axis, pointing up in
                                                         ///< the image (y <= 0)
  int confidence = 0;  ///< points of the peduncle cluster: the more, the better supported
};

/// One bunch's result.
struct GrapeBunch {
  Box2D roi;                               ///< pixels (Eq. 1, merged, clipped to the image)
  Cloud cloud;                             ///< m, camera frame; colours, normals, segmenter labels
  std::optional<GrapeCutPoint> cut_point;  ///< none: no peduncle cluster of min_points points
};

/// One frame's result.
struct GrapeFrameResult {
  std::vector<GrapeDetection> detections;  ///< the boxes used (detector's, or as given)
  std::vector<GrapeDetection> outside;     ///< bunch / peduncle boxes wholly outside the image
  std::vector<GrapeBunch> bunches;         ///< one per ROI with at least 3 points, in ROI order
};

/// Step 5 alone: the cut point of a labelled cloud (m). The points labelled
/// cfg.peduncle_label are clustered (Euclidean, cfg.cluster_tolerance); the largest cluster
/// gives the position (its centroid), the direction (its principal axis, sign chosen so that
/// it points up in the image: toward -y; an exactly horizontal axis points toward +x) and the
/// confidence (its point count). No peduncle point, or a largest cluster of fewer than
/// cfg.min_points points: std::nullopt (the bunch still has its labelled cloud). Ties between
/// clusters of one size go to the one with the smallest point index. Throws Error when the
/// cloud has no labels.
std::optional<GrapeCutPoint> grape_cut_point(const Cloud& cloud, const GrapeCutPointConfig& cfg = {});

/// The project's grape detector's boxes as GrapeDetections: category = class_id + 1 (class 0
/// grape → 1 bunch, class 1 peduncle → 2), as `detect objects` writes COCO category ids; the box
/// is the smallest pixel box covering the continuous one.
std::vector<GrapeDetection> grape_detections(const std::vector<Detection2D>& boxes);

class GrapePipeline {
 public:
  /// Validates `cfg` (Error(where, ...)). `detector` may be null when every call gives its boxes.
  GrapePipeline(GrapePipelineConfig cfg, GrapeSegmenter segmenter, std::unique_ptr<Detector2D> detector = nullptr,
                const std::string& where = "grape pipeline config");
  ~GrapePipeline();
  GrapePipeline(GrapePipeline&&) noexcept;
  GrapePipeline& operator=(GrapePipeline&&) noexcept;

  /// Every step on one frame (colour required, registered to depth), boxes from the detector.
  /// Throws Error when the pipeline has no detector, or as the boxes' overload.
  GrapeFrameResult process(const RgbdFrame& frame);
  /// Every step but the detection, on the boxes given. Throws Error for a frame without colour
  /// or whose colour, depth and camera sizes differ.
  GrapeFrameResult process(const RgbdFrame& frame, const std::vector<GrapeDetection>& detections) const;

  const GrapePipelineConfig& config() const { return cfg_; }
  const GrapeSegmenter& segmenter() const { return segmenter_; }
  bool has_detector() const { return detector_ != nullptr; }

 private:
  GrapePipelineConfig cfg_;
  GrapeSegmenter segmenter_;
  std::unique_ptr<Detector2D> detector_;
};

}  // namespace cropsight::pipeline
