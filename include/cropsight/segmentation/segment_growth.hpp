#pragma once
// Completing a segment over the pixels no segment holds (docs/pipelines/broccoli-heads.md,
// "Completing fragmented heads").
//
// An organised clustering with a fixed neighbour tolerance breaks a rough or noisy surface (a
// broccoli head's florets under ToF noise at 1 m) into one kept segment and many pieces below the
// minimum size, which are dropped. A classifier then recognises the kept piece, but its mask covers
// only part of the object. grow_into_free_pixels extends chosen segments over the dropped pixels
// around them: a 4-neighbour flood fill from the segment's pixels into valid pixels that belong to
// no segment, joining neighbours closer than a (looser) 3D tolerance and staying within a 3D
// radius of the segment's centroid. Pixels of other kept segments are never taken, so a segment
// cannot swallow a neighbour that the clustering isolated (a leaf), only the debris between them.
#include <span>
#include <vector>

#include "cropsight/core/organized_cloud.hpp"
#include "cropsight/core/segment.hpp"

namespace cropsight::segmentation {

struct SegmentGrowthOptions {
  float tolerance = 0.013f;  ///< m; max 3D distance between 4-neighbours joined by the growth
  float radius = 0.1f;       ///< m; grown pixels lie within this distance of the segment's centroid
};

/// Reusable buffers (no allocation per frame once warm). Not thread-safe.
struct SegmentGrowthWorkspace {
  std::vector<int> owner;  // per pixel: segment index or -1
  std::vector<int> queue;
};

/// Grows `*segments[k]` for each k of `grow` (in that order: an earlier one claims contested pixels
/// first) over the valid pixels of `cloud` that belong to no segment of `segments` (the segments
/// are passed by pointer because callers keep them inside larger records). Indices stay ascending;
/// the summaries (centroid, bounds, box) are recomputed for the grown segments. Returns the number
/// of pixels added. Throws Error when an index lies outside the cloud or `grow` names no segment.
std::size_t grow_into_free_pixels(const OrganizedCloud& cloud, std::span<Segment* const> segments,
                                  std::span<const int> grow, const SegmentGrowthOptions& options,
                                  SegmentGrowthWorkspace& ws);

/// The same with the caller's owner map (one int per pixel: the index into `segments` of the
/// segment holding it, or -1; e.g. the flood fill's label image, FloodFillWorkspace::labels, when
/// `segments` are its segments in order), which saves building it. Grown pixels are written into
/// `owner`. Pixels without a valid point never join, whatever `owner` says of them.
std::size_t grow_into_free_pixels(const OrganizedCloud& cloud, std::span<Segment* const> segments,
                                  std::span<const int> grow, const SegmentGrowthOptions& options, std::span<int> owner,
                                  std::vector<int>& queue);

}  // namespace cropsight::segmentation
