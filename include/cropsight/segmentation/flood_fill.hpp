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
  std::vector<int> stack;    // pixel indices to expand (each pixel is pushed at most once)
  std::vector<int> columns;  // their columns (saves a division per pixel)
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
  // Pixels of rejected segments get -2 while filling so that they are never seeded again.
  ws.labels.assign(std::size_t(n), -1);
  // Every pixel enters the stack and the member list at most once: fixed-size buffers, no
  // capacity checks in the loop.
  if (ws.stack.size() < std::size_t(n)) ws.stack.resize(std::size_t(n));
  if (ws.columns.size() < std::size_t(n)) ws.columns.resize(std::size_t(n));
  if (ws.members.size() < std::size_t(n)) ws.members.resize(std::size_t(n));
  int* labels = ws.labels.data();
  int* stack = ws.stack.data();
  int* cols = ws.columns.data();
  int* members = ws.members.data();
  std::vector<Segment> out;
  int seg_id = 0;
  bool rejected_any = false;
  for (int s = 0, su = 0; s < n; ++s, su = (su + 1 == width ? 0 : su + 1)) {
    if (labels[s] != -1 || !pred.seed(s)) continue;
    int top = 0, count = 0;
    labels[s] = seg_id;
    members[count++] = s;
    stack[top] = s, cols[top] = su, ++top;
    while (top > 0) {
      --top;
      const int p = stack[top], u = cols[top];
      if (!pred.expands(p)) continue;
      // 4-neighbours, bounds checked on the grid (no wrap from a row end to the next row).
      auto visit = [&](int q, int qu) {
        if (labels[q] != -1 || !pred.member(q) || !pred.similar(p, q)) return;
        labels[q] = seg_id;
        members[count++] = q;
        stack[top] = q, cols[top] = qu, ++top;
      };
      if (u > 0) visit(p - 1, u - 1);
      if (u + 1 < width) visit(p + 1, u + 1);
      if (p >= width) visit(p - width, u);
      if (p + width < n) visit(p + width, u);
    }
    if (count >= min_size && count <= max_size) {
      Segment seg;
      seg.indices.assign(members, members + count);
      out.push_back(std::move(seg));
      ++seg_id;
    } else {
      for (int k = 0; k < count; ++k) labels[members[k]] = -2;
      rejected_any = true;
    }
  }
  if (rejected_any)
    for (int i = 0; i < n; ++i) labels[i] = labels[i] == -2 ? -1 : labels[i];
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
