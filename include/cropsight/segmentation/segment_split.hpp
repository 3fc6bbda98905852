#pragma once
// Splitting segments again along extra barrier pixels (e.g. geometry::mark_concave_creases): a
// second, finer look at chosen segments of an organised clustering, such as the clusters a
// classifier rejected, where a head and the leaf touching it were one surface to the first pass.
#include <cstdint>
#include <span>
#include <vector>

#include "cropsight/core/organized_cloud.hpp"
#include "cropsight/core/segment.hpp"

namespace cropsight::segmentation {

/// A piece of a split segment and the index (into the `segments` passed) of the segment it came from.
struct SplitPiece {
  int parent = -1;
  Segment segment;
};

/// Reusable buffers (no allocation per frame once warm). Not thread-safe.
struct SegmentSplitWorkspace {
  std::vector<int> owner;    // per pixel: -1, except during a call
  std::vector<int> members;  // the piece being filled (the queue: pixel, column pairs)
  std::vector<int> remap;    // fill attempt of the current target -> piece, or -1
};

/// Splits each segment `*segments[k]` for k in `targets` along the pixels marked non-zero in
/// `barrier` (one entry per pixel of `cloud`): its unmarked valid pixels are flood-filled, and
/// 4-neighbours join when both belong to the same segment and lie closer than `tolerance` (m).
/// Returns the pieces of min_size..max_size points, each with its parent, indices ascending,
/// summaries filled, in raster order of their first pixel. A segment without barrier pixels comes
/// back whole (as one piece, when its size is in range). Throws Error("segment split", ...) for a
/// bad size range, a barrier of the wrong size, or a target or index outside the input.
std::vector<SplitPiece> split_segments(const OrganizedCloud& cloud, std::span<const Segment* const> segments,
                                       std::span<const int> targets, std::span<const std::uint8_t> barrier,
                                       float tolerance, int min_size, int max_size, SegmentSplitWorkspace& ws);

}  // namespace cropsight::segmentation
