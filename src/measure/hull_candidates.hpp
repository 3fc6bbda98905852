#pragma once
// Candidate vertices of the 3D convex hull of points from an organised cloud, found without
// building the hull (internal to the measure module; used by HeadSizer before qhull).
//
// Why: a hull of a broccoli head's ~2500 points costs 0.4 ms (our Quickhull) to 1.5 ms (qhull),
// against a per-frame budget of 0.5 ms for sizing and tracking together, and ~80 % of
// those points cannot be hull vertices.
//
// Why it is exact: a vertex of the hull of a set is a vertex of the hull of every subset that
// contains it (the direction it is extreme in still singles it out). In a pinhole deprojection
// the pixels of one image row lie on a plane through the camera centre, and so do those of one
// column. The projective map (x, y, z) -> (x/z, y/z, 1/z) keeps convexity for z > 0 and turns
// x/z into an affine function of the column u (y/z of the row v), so a row's 2D hull has the
// vertices of the points (u, 1/z) — already sorted by u, so Andrew's monotone chain needs no
// sort. A point that is not a vertex of its row's hull or of its column's hull is not a vertex of
// the 3D hull. The hull is then built from the survivors (~20 % of a simulated head's points;
// the column pass runs on the row pass's survivors, a subset, so it stays exact) and has the same
// vertices as the hull of all points.
//
// The precondition (x/z affine in u and y/z affine in v to float rounding: a pinhole deprojection
// without lens distortion, which is what to_organized_cloud produces) is checked on the points;
// when it fails, or the set is too small or a single row/column, the result is empty-optional and
// the caller gives qhull every point. Rounding is absorbed by a tolerance that keeps borderline
// points (the filter may keep a non-vertex, never drop a vertex beyond float rounding).
//
// Thread-safety: a pure function.
#include <optional>
#include <vector>

namespace cropsight {
struct OrganizedCloud;
}

namespace cropsight::measure {

/// `indices`: pixel indices of valid (finite) points of `cloud`, each at most once, any order.
/// Returns the subset (ascending pixel index) that can be vertices of their 3D convex hull, or
/// nullopt when the pinhole structure does not hold (see above).
std::optional<std::vector<int>> hull_vertex_candidates(const OrganizedCloud& cloud, const std::vector<int>& indices);

}  // namespace cropsight::measure
