#pragma once
// Geometric features of a segment (after Kusumam et al. 2017 §4.2.4), 5 values, computed from an
// organised segment with normals. Definitions (ours, precise):
//  0 area        m². Surface area of the segment: the sum of the areas of the two triangles
//                (p00,p10,p11), (p00,p11,p01) of every 2×2 pixel block whose four pixels are all
//                in the segment (the organised mesh), so it does not depend on the camera model.
//  1 compactness 4π·A/P² of the segment's pixel mask (1 for a disc, smaller for elongated or
//                ragged masks), A = mask pixels, P = (π/4)·(number of pixel sides between a mask
//                pixel and a non-mask pixel) — the π/4 factor makes the 4-connected boundary of a
//                digital disc measure close to its circumference.
//  2 smoothness  rad. Mean angle between the normals of 4-adjacent segment pixels (0 = planar).
//  3 convexity   fraction in [0, 1] of 4-adjacent segment pixel pairs (i, j) that are locally
//                convex, (p_j - p_i)·(n_j - n_i) > 0 (a dome facing the camera ≈ 1, a bowl ≈ 0;
//                pairs with |value| ≤ 1e-12 m count one half).
//  4 symmetry    in (0, 1]. exp(-(|γ1| + |γ2|)/2) with γ1, γ2 the skewness of the points'
//                coordinates along the two major principal axes (PCA of the segment); 1 = the
//                point distribution is symmetric about both axes.
// Pixels without a finite normal are ignored by 2 and 3; fewer than 3 usable points → zeros.
#include <array>
#include <span>
#include <string>

#include "cropsight/core/organized_cloud.hpp"

namespace cropsight::features {

inline constexpr int kGeometricFeatures = 5;
inline const std::array<std::string, kGeometricFeatures>& geometric_feature_names() {
  static const std::array<std::string, kGeometricFeatures> names{"area", "compactness", "smoothness", "convexity",
                                                                 "symmetry"};
  return names;
}

/// Reusable mask buffer (per frame size); not thread-safe.
struct GeometricWorkspace {
  std::vector<unsigned char> mask;  // width·height, cleared after each call
};

/// Writes kGeometricFeatures floats to `out`. `indices` are pixel indices of valid points.
void compute_geometric_features(const OrganizedCloud& cloud, std::span<const int> indices, GeometricWorkspace& ws,
                                float* out);

}  // namespace cropsight::features
