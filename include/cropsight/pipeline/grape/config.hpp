#pragma once
// The grape pipeline's one configuration (configs/grape-camera.yaml, --set key=value): the ROI
// and its cloud (roi.*), the segmenter (segmenter.*: which model and how it runs; by default the
// shipped ensemble of configs/grape-best.yaml, make_pipeline.hpp) and the cut point (cut_point.*).
#include <string>

#include "cropsight/core/config.hpp"
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

/// The whole pipeline's config. `segmenter` is what the pipeline's Segmenter was built from: a
/// preset's or --set's segmenter.* keys are laid over the segmenter preset or model the spec names
/// (make_pipeline), and Pipeline's constructor records the Segmenter it is given.
struct Config {
  RoiConfig roi;
  SegmenterConfig segmenter;
  CutPointConfig cut_point;

  template <class V>
  void visit(V& v) {
    v("roi", roi, "steps 1-3: ROI from the boxes (Eq. 1), its coloured cloud (Algorithm 1) and normals");
    v("segmenter", segmenter, "step 4: the per-point segmenter (default: the shipped ensemble, grape-best)");
    v("cut_point", cut_point, "step 5: the cut point on the labelled peduncle");
  }
  /// Throws Error(where, ...) naming the first key out of range (roi.validate's rules included).
  /// The segmenter's keys are checked when its models load (Segmenter's constructor).
  void validate(const std::string& where) const;
};

}  // namespace cropsight::pipeline::grape
