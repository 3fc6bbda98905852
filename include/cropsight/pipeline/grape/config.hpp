#pragma once
// The grape pipeline's one configuration (configs/grape-camera.yaml, --set key=value): the ROI
// and its cloud (roi.*), the segmenter (segmenter.*: which model and how it runs; by default the
// shipped ensemble of configs/grape-best.yaml, make_pipeline.hpp) and the cut point (cut_point.*).
#include <string>

#include "cropsight/core/config.hpp"
#include "cropsight/nn/center_backend.hpp"
#include "cropsight/pipeline/grape/roi.hpp"
#include "cropsight/pipeline/grape/segmenter.hpp"

namespace cropsight::pipeline::grape {

/// Where to cut a bunch: on its peduncle, found as the largest Euclidean cluster of the points
/// the segmenter labels peduncle.
struct CutPointConfig {
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

/// How the pipeline's 2D detector runs (the model itself is the spec's `detector`, make_pipeline.hpp).
struct DetectorConfig {
  /// auto: the libtorch plugin on the model's .pt weights where the plugin is installed, OpenCV
  /// DNN on its .onnx otherwise (nn::open_center_detector). Same boxes within float rounding;
  /// libtorch takes about half OpenCV DNN's time on the shipped grape model (2-core Intel Xeon,
  /// docs/pipelines/detector.md), but on a CPU busy with other work its OpenMP threads spin while
  /// they wait unless OMP_WAIT_POLICY=PASSIVE is set at launch: opencv is the choice there.
  nn::DetectorRuntime backend = nn::DetectorRuntime::automatic;

  template <class V>
  void visit(V& v) {
    v("backend", backend,
      "auto | libtorch | opencv: runtime of a detector given by name (auto: libtorch where its plugin is "
      "installed, about twice as fast; a .pt or .onnx file picks its own)");
  }
};

/// The whole pipeline's config. `segmenter` is what the pipeline's Segmenter was built from: a
/// preset's or --set's segmenter.* keys are laid over the segmenter preset or model the spec names
/// (make_pipeline), and Pipeline's constructor records the Segmenter it is given.
struct Config {
  RoiConfig roi;
  SegmenterConfig segmenter;
  CutPointConfig cut_point;
  DetectorConfig detector;

  template <class V>
  void visit(V& v) {
    v("roi", roi, "steps 1-3: ROI from the boxes (Eq. 1), its coloured cloud (Algorithm 1) and normals");
    v("segmenter", segmenter, "step 4: the per-point segmenter (default: the shipped ensemble, grape-best)");
    v("cut_point", cut_point, "step 5: the cut point on the labelled peduncle");
    v("detector", detector, "step 1: the 2D detector's runtime (its model is --detector)");
  }
  /// Throws Error(where, ...) naming the first key out of range (roi.validate's rules included).
  /// The segmenter's keys are checked when its models load (Segmenter's constructor).
  void validate(const std::string& where) const;
};

}  // namespace cropsight::pipeline::grape
