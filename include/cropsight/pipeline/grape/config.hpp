#pragma once
// The grape pipeline's configuration (configs/grape-camera.yaml, --set key=value): the ROI and
// its cloud (roi.*) and the cut point (cut_point.*). The segmenter has its own configuration
// (segmenter.hpp, configs/grape-best.yaml), set through make_pipeline's segmenter.* keys.
#include <string>

#include "cropsight/core/config.hpp"
#include "cropsight/pipeline/grape/roi.hpp"

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

/// The whole pipeline's config (configs/grape-camera.yaml). The segmenter has its own
/// (SegmenterConfig, configs/grape-best.yaml): it is built once and handed to the pipeline.
struct Config {
  RoiConfig roi;
  CutPointConfig cut_point;

  template <class V>
  void visit(V& v) {
    v("roi", roi, "steps 1-3: ROI from the boxes (Eq. 1), its coloured cloud (Algorithm 1) and normals");
    v("cut_point", cut_point, "step 5: the cut point on the labelled peduncle");
  }
  /// Throws Error(where, ...) naming the first key out of range (roi.validate's rules included).
  void validate(const std::string& where) const;
};

}  // namespace cropsight::pipeline::grape
