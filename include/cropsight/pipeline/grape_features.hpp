#pragma once
// Per-point features of the classical grape segmentation model (issue 6, stage 5): colour,
// normal, position in the normalised ROI cloud, and at two neighbourhood radii the local
// covariance eigen-features, neighbourhood colour statistics and FPFH (PCL). Radii are in the
// neighbourhood sizes are point counts (k nearest neighbours), not radii: the dataset's clouds
// are extremely uneven in density (median nearest-neighbour spacing 0.001 unit-sphere units,
// yet 200-1800 points within 0.01), so a fixed radius gives either empty or huge neighbourhoods.
#include <string>
#include <vector>

#include "cropsight/core/cloud.hpp"

namespace cropsight::pipeline {

struct GrapeFeatureConfig {
  int k_small = 16;  ///< points; fine neighbourhood
  int k_large = 64;  ///< points; coarse neighbourhood
  bool fpfh = true;  ///< include the 2 × 33 FPFH bins
  int threads = 2;   ///< OpenMP threads of PCL's FPFH

  template <class V>
  void visit(V& v) {
    v("k_small", k_small, "points; fine neighbourhood size (ours)");
    v("k_large", k_large, "points; coarse neighbourhood size (ours)");
    v("fpfh", fpfh, "bool; add FPFH histograms at both radii");
    v("threads", threads, "count; threads of the FPFH computation");
  }
  /// "k_small=16;k_large=64;fpfh=1": stored inside model files.
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
