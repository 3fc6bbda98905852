#pragma once
// Concave creases of an organised cloud: the valleys where two surfaces meet, after the convexity
// rule of LCCP (Stein et al. 2014, "Object partitioning using local convexity"). Two points p, q
// with unit normals facing the camera form a valley when (n_p - n_q)·(p - q) < 0: their normals
// lean towards each other. A dome (a broccoli head) is convex everywhere at the normals'
// smoothing scale, so the rule marks where a leaf runs into it, and not its top; florets' bumps
// are smaller than the integral normals' window and do not show.
#include <cstdint>
#include <span>
#include <vector>

#include "cropsight/core/organized_cloud.hpp"

namespace cropsight::geometry {

struct ConcaveCreaseOptions {
  float angle_deg = 30.0f;  ///< degrees; pairs whose normals differ by more (and face each other) are creases
  int step = 3;             ///< pixels between the two points compared (right and down of each pixel)
};

/// For each pixel p of `pixels` (indices into `cloud`), compares it with the pixels `step` to its
/// right and `step` below it; where the pair is a concave crease, sets `marks` of both to 1.
/// `marks` must hold cloud.size() entries and is only ever set, never cleared (the caller clears
/// it). Pixels without a normal (NaN) are never creases. Needs cloud.nx/ny/nz.
/// Throws Error("concave creases", ...) for a bad option or a cloud without normals.
void mark_concave_creases(const OrganizedCloud& cloud, std::span<const int> pixels, const ConcaveCreaseOptions& options,
                          std::span<std::uint8_t> marks);

}  // namespace cropsight::geometry
