#pragma once
// 3D convex hull by Quickhull (Barber, Dobkin & Huhdanpaa 1996, the algorithm qhull implements),
// written for the head-sizing hot path (internal to the measure module).
//
// Why not qhull: on a broccoli head's hull candidates (~450 points, ~300 vertices) qhull takes
// ~1 ms, mostly per-facet bookkeeping (set allocation, neighbour matching, facet merging), and a
// frame shows ~5 heads, against the 0.5 ms per frame budget of sizing and tracking.
// This version keeps faces in one array, outside sets as linked lists through one index array,
// and finds the horizon by a depth-first walk, so nothing is allocated per facet.
//
// Precision: distances are computed in double on the float inputs and a point counts as outside
// a face only when it lies more than `eps` (1e-12 × the largest coordinate magnitude) above it,
// so points exactly on a face (coplanar input, e.g. millimetre-quantised depth) are not vertices,
// while points pushed out by float rounding (~1e-8 m) are, as in qhull. The hull is checked
// (closed, Euler's formula); any inconsistency returns false and the caller uses qhull, as it
// does for flat or tiny sets. tests/measure/test_quickhull.cpp compares it with qhull
// (pcl::ConvexHull) on the same inputs.
//
// Thread-safety: a pure function.
#include <Eigen/Core>
#include <array>
#include <vector>

namespace cropsight::measure {

struct QuickHull {
  std::vector<int> vertices;                  ///< indices into the input, ascending
  std::vector<std::array<int, 3>> triangles;  ///< faces, counter-clockwise seen from outside
};

/// Hull of `points` (metres). Returns false (and leaves `out` unspecified) for fewer than 4
/// points, a flat or collinear set, or a numerically inconsistent hull.
bool quickhull(const std::vector<Eigen::Vector3f>& points, QuickHull& out);

}  // namespace cropsight::measure
