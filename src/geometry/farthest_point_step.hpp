#pragma once
// Private helper: one step of farthest-point sampling over points stored as three planes, in a
// baseline loop and an AVX2 one (src/core/cpu_dispatch.hpp, form 2). Not a public header.
#include <cstddef>

namespace cropsight::geometry::detail {

/// Lowers dist[i] to the Euclidean distance from point i (x[i], y[i], z[i]) to the centre
/// (cx, cy, cz) where that is smaller, for every i < n, and returns the first index of the largest
/// dist (a chosen point carries a negative dist and so is never returned while an unchosen one
/// is left). The distance is computed as Eigen's (p - c).norm() computes it for a Vector3f,
/// sqrt(dx² + (dy² + dz²)) without FMA, so both variants reproduce the original scalar loop bit
/// for bit. allow_avx2 = false forces the baseline loop (tests compare the two).
std::size_t farthest_point_step(const float* x, const float* y, const float* z, float* dist, std::size_t n, float cx,
                                float cy, float cz, bool allow_avx2 = true);

}  // namespace cropsight::geometry::detail
