#pragma once
// Clustered Viewpoint Feature Histogram (Aldoma et al. 2011). This calls pcl::CVFHEstimation
// (PCL is the real implementation; CVFH needs its own normal re-estimation and smooth-region
// clustering, which we do not duplicate). CVFH yields one 308-bin histogram per stable smooth
// region of the segment; to give a fixed-size feature we return their element-wise MEAN (one
// histogram when PCL finds no region and falls back to the whole segment).
#include <span>
#include <vector>

#include "cropsight/core/organized_cloud.hpp"

namespace cropsight::features {

inline constexpr int kCvfhBins = 308;

struct CvfhConfig {
  float eps_angle = 0.125f;           ///< rad; smooth-region normal deviation (PCL default 0.125)
  float curvature_threshold = 0.03f;  ///< points above are left out of regions (PCL default 0.03)
  float cluster_tolerance = 0.015f;   ///< m; region growing distance (PCL default 3·leaf 0.005)
  float radius_normals = 0.015f;      ///< m; normal re-estimation radius (PCL default 3·leaf 0.005)
  int min_points = 50;                ///< smallest region (PCL default 50)
  bool normalize_bins = false;        ///< PCL default false

  template <class V>
  void visit(V& v) {
    v("eps_angle", eps_angle, "rad; max normal deviation inside a smooth region (PCL CVFHEstimation default 0.125)");
    v("curvature_threshold", curvature_threshold,
      "curvature above which points are excluded from regions (PCL default 0.03)");
    v("cluster_tolerance", cluster_tolerance, "m; region growing distance (PCL default 0.015)");
    v("radius_normals", radius_normals, "m; normal re-estimation radius (PCL default 0.015)");
    v("min_points", min_points, "points; smallest smooth region (PCL default 50)");
    v("normalize_bins", normalize_bins, "normalise bins by point count (PCL CVFHEstimation default false)");
  }
};

/// CVFH of the valid points (finite position and normal) among `indices`; writes kCvfhBins
/// floats (mean over regions) to `out`; zeros when fewer than 2 usable points. Requires normals
/// and curvature in `cloud`.
void compute_cvfh(const OrganizedCloud& cloud, std::span<const int> indices, const CvfhConfig& cfg, float* out);

}  // namespace cropsight::features
