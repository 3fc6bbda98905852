#pragma once
// Viewpoint-angle histogram (Kusumam et al. 2017): for each point, the angle θ ∈ [0, π/2]
// between its normal and the unit vector from the point to the camera (normals face the camera,
// so θ ≤ π/2). 12 bins of 7.5° over [0, π/2] (θ = π/2 goes in the last bin); each bin holds the
// FRACTION of usable points (sum 1), so the feature does not depend on segment size.
#include <span>

#include "cropsight/core/organized_cloud.hpp"

namespace cropsight::features {

inline constexpr int kViewpointAngleBins = 12;

/// Writes kViewpointAngleBins floats to `out`; all zeros when no point has a finite normal.
/// Angles above π/2 (a normal facing away, possible only for foreign normals) are clamped.
void compute_viewpoint_angle_histogram(const OrganizedCloud& cloud, std::span<const int> indices, float* out);

}  // namespace cropsight::features
