#pragma once
// Per-point features of the classical grape segmentation model (issue 6, stage 5): colour,
// normal, position in the normalised ROI cloud, and at two neighbourhood radii the local
// covariance eigen-features, neighbourhood colour statistics and FPFH (PCL). Radii are in the
// cloud's units (the dataset's clouds are normalised to the unit sphere).
#include <string>
#include <vector>

#include "cropsight/core/cloud.hpp"

namespace cropsight::pipeline {

struct GrapeFeatureConfig {
  double radius_small = 0.03;  ///< unit-sphere units; fine neighbourhood (berry scale)
  double radius_large = 0.07;  ///< unit-sphere units; coarse neighbourhood (bunch / leaf scale)
  bool fpfh = true;            ///< include the 2 × 33 FPFH bins
  int threads = 2;             ///< OpenMP threads of PCL's FPFH

  template <class V>
  void visit(V& v) {
    v("radius_small", radius_small, "unit-sphere units; fine neighbourhood radius (ours; tuned by k-fold)");
    v("radius_large", radius_large, "unit-sphere units; coarse neighbourhood radius (ours; tuned by k-fold)");
    v("fpfh", fpfh, "bool; add FPFH histograms at both radii");
    v("threads", threads, "count; threads of the FPFH computation");
  }
  /// "radius_small=0.03;radius_large=0.07;fpfh=1": stored inside model files.
  std::string recipe() const;
  static GrapeFeatureConfig from_recipe(const std::string& text, const std::string& where);
};

/// Number of features per point for `cfg`.
std::size_t grape_feature_count(const GrapeFeatureConfig& cfg);
/// Feature names, in column order (for documentation and importance dumps).
std::vector<std::string> grape_feature_names(const GrapeFeatureConfig& cfg);

/// Row-major features (rows = subset.size(), or every point when `subset` is empty). Needs
/// normals and colours in `cloud`; neighbourhoods use the whole cloud. Throws Error otherwise.
std::vector<float> grape_point_features(const Cloud& cloud, const GrapeFeatureConfig& cfg,
                                        const std::vector<int>& subset = {});

}  // namespace cropsight::pipeline
