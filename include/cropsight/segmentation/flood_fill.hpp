#pragma once
// One organised labeller for every organised clustering (Algorithm 1 of Montes et al. 2020,
// "Real-time detection of broccoli crops in 3D point clouds"; design after depth_clustering:
// one labeller, a pluggable similarity predicate). A 4-neighbour flood fill over the pixel grid:
//
//   for every pixel s in raster order that is unlabelled and pred.seed(s):
//     new label L; push s
//     while the stack is not empty: pop p; if pred.expands(p): for each 4-neighbour q of p
//       that is unlabelled and pred.member(q) and pred.similar(p, q): label q with L, push q
//   keep the labels whose size lies in [min_size, max_size]
//
// The predicate is a template parameter (inlined, no virtual call per pixel):
//
//   struct Pred {
//     bool member(int q) const;          // q may belong to a segment at all (e.g. valid point)
//     bool seed(int s) const;            // a new segment may start at s (implies member)
//     bool expands(int p) const;         // growth continues from p (ORG: low curvature)
//     bool similar(int p, int q) const;  // neighbour q joins p's segment
//   };
//
// A pixel that does not expand can still be absorbed by a neighbour's segment (it becomes part
// of the segment, as in PCL's region growing) but never grows it further.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "cropsight/core/error.hpp"
#include "cropsight/core/organized_cloud.hpp"
#include "cropsight/core/segment.hpp"

namespace cropsight::segmentation {

/// Reusable buffers for flood_fill (no allocation per frame once warm). Not thread-safe.
struct FloodFillWorkspace {
  /// Per pixel: index into the returned segments, or -1 (unlabelled / in a rejected segment).
  std::vector<int> labels;
  std::vector<int> stack;
  std::vector<int> members;  // pixels of the segment being grown
};

/// Labels `width`×`height` pixels with `pred`; returns the segments with
/// min_size ≤ size ≤ max_size, in order of their seed pixel (raster order), indices in fill
/// order. ws.labels holds the segment id per pixel afterwards. Does not fill the summaries
/// (call summarize() on the ones you keep, or use flood_fill_segments below).
template <class Pred>
std::vector<Segment> flood_fill(int width, int height, const Pred& pred, int min_size, int max_size,
                                FloodFillWorkspace& ws) {
  if (width <= 0 || height <= 0) return {};
  if (min_size < 1 || max_size < min_size)
    throw Error("flood fill", "size range must satisfy 1 <= min_size <= max_size");
  const int n = width * height;
  // Pixels that were tried and rejected get -2 so that they are never seeded again.
  ws.labels.assign(std::size_t(n), -1);
  ws.stack.clear();
  std::vector<Segment> out;
  int seg_id = 0;
  for (int s = 0; s < n; ++s) {
    if (ws.labels[s] != -1 || !pred.seed(s)) continue;
    ws.members.clear();
    ws.members.push_back(s);
    ws.labels[s] = seg_id;
    ws.stack.push_back(s);
    while (!ws.stack.empty()) {
      const int p = ws.stack.back();
      ws.stack.pop_back();
      if (!pred.expands(p)) continue;
      const int u = p % width;
      // Neighbours: left, right, up, down (bounds checked on the grid, not by index wrap).
      const int nb[4] = {u > 0 ? p - 1 : -1, u + 1 < width ? p + 1 : -1, p >= width ? p - width : -1,
                         p + width < n ? p + width : -1};
      for (int q : nb) {
        if (q < 0 || ws.labels[q] != -1) continue;
        if (!pred.member(q) || !pred.similar(p, q)) continue;
        ws.labels[q] = seg_id;
        ws.members.push_back(q);
        ws.stack.push_back(q);
      }
    }
    const int size = int(ws.members.size());
    if (size >= min_size && size <= max_size) {
      Segment seg;
      seg.indices = ws.members;
      out.push_back(std::move(seg));
      ++seg_id;
    } else {
      for (int q : ws.members) ws.labels[q] = -2;
    }
  }
  for (int& l : ws.labels)
    if (l == -2) l = -1;
  return out;
}

/// flood_fill over `cloud`'s grid, then summarize() on every kept segment.
template <class Pred>
std::vector<Segment> flood_fill_segments(const OrganizedCloud& cloud, const Pred& pred, int min_size, int max_size,
                                         FloodFillWorkspace& ws) {
  auto segs = flood_fill(cloud.width, cloud.height, pred, min_size, max_size, ws);
  for (auto& s : segs) summarize(s, cloud);
  return segs;
}

}  // namespace cropsight::segmentation
