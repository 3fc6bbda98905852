#pragma once
// One organised labeller for every organised clustering (Algorithm 1 of Montes et al. 2020,
// "Real-time detection of broccoli crops in 3D point clouds"; design after depth_clustering:
// one labeller, a pluggable similarity predicate). A 4-neighbour flood fill over the pixel grid:
//
//   for every pixel s in raster order that is unlabelled and pred.seed(s):
//     new label L; enqueue s
//     while the queue is not empty: take p; if pred.expands(p): for each 4-neighbour q of p
//       that is unlabelled and pred.member(q) and pred.similar(p, q): label q with L, enqueue q
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
//
// A predicate may instead provide `std::uint8_t links(int p) const` (LinkBits: similar() and the
// grid bounds for the four neighbours of p, and member() — precomputed for the whole image in a
// vectorised pass, which requires similar() to be symmetric); the fill then reads one byte per
// pixel instead of evaluating similar() per neighbour.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "cropsight/core/error.hpp"
#include "cropsight/core/organized_cloud.hpp"
#include "cropsight/core/segment.hpp"

namespace cropsight::segmentation {

/// Reusable buffers for flood_fill (no allocation per frame once warm). Not thread-safe.
struct FloodFillWorkspace {
  /// Per pixel: index into the returned segments, or -1 (unlabelled / in a rejected segment).
  std::vector<int> labels;
  std::vector<int> members;  // pixels of the segment being grown, in BFS order (also the queue)
  std::vector<int> columns;  // their columns (saves a division per pixel)
  std::vector<int> remap;    // fill attempt → kept segment id or -1
  std::vector<int*> slots;   // final pass: next index slot per kept segment (+ a dummy)
};

/// Link bits of a pixel for predicates that precompute similar() per 4-neighbour pair (see
/// flood_fill's header comment): neighbour to the right / left / below / above joins, and
/// "member". Links across the grid border are 0.
enum LinkBits : std::uint8_t { kLinkRight = 1, kLinkLeft = 2, kLinkDown = 4, kLinkUp = 8, kLinkMember = 16 };

/// Labels `width`×`height` pixels with `pred`; returns the segments with
/// min_size ≤ size ≤ max_size, in order of their seed pixel (raster order), indices ascending
/// (raster order). ws.labels holds the segment id per pixel afterwards. Does not fill the summaries
/// (call summarize() on the ones you keep, or use flood_fill_segments below).
template <class Pred>
std::vector<Segment> flood_fill(int width, int height, const Pred& pred, int min_size, int max_size,
                                FloodFillWorkspace& ws) {
  if (width <= 0 || height <= 0) return {};
  if (min_size < 1 || max_size < min_size)
    throw Error("flood fill", "size range must satisfy 1 <= min_size <= max_size");
  const int n = width * height;
  // One pass evaluates member() for every pixel, so that the fill loop tests a neighbour with a
  // single load: -1 = unlabelled member, -3 = not a member, >= 0 = fill attempt number. Attempts
  // whose size is out of range are not relabelled pixel by pixel (scattered writes over e.g. the
  // whole ground); one sequential pass at the end maps attempts to kept segment ids or -1.
  ws.labels.resize(std::size_t(n));
  int* labels = ws.labels.data();
  for (int i = 0; i < n; ++i) labels[i] = pred.member(i) ? -1 : -3;
  // Every pixel enters the member list (the BFS queue) at most once: fixed-size buffers, no
  // capacity checks in the loop.
  if (ws.columns.size() < std::size_t(n)) ws.columns.resize(std::size_t(n));
  if (ws.members.size() < std::size_t(n)) ws.members.resize(std::size_t(n));
  int* cols = ws.columns.data();
  int* members = ws.members.data();
  std::vector<Segment> out;
  ws.remap.clear();
  int attempt = 0;
  for (int s = 0; s < n; ++s) {
    if (labels[s] != -1 || !pred.seed(s)) continue;  // seed() implies member()
    const int su = s % width;
    // Breadth-first: the member list is the queue (each pixel enters it once), which keeps the
    // frontier compact in memory.
    int head = 0, count = 0;
    labels[s] = attempt;
    members[count] = s, cols[count] = su, ++count;
    while (head < count) {
      const int p = members[head], u = cols[head];
      ++head;
      if (!pred.expands(p)) continue;
      if constexpr (requires { pred.links(p); }) {
        const std::uint8_t b = pred.links(p);
        auto visit = [&](int q, int qu) {
          if (labels[q] != -1) return;
          labels[q] = attempt;
          members[count] = q, cols[count] = qu, ++count;
        };
        if (b & kLinkLeft) visit(p - 1, u - 1);
        if (b & kLinkRight) visit(p + 1, u + 1);
        if (b & kLinkUp) visit(p - width, u);
        if (b & kLinkDown) visit(p + width, u);
      } else {
        // 4-neighbours, bounds checked on the grid (no wrap from a row end to the next row).
        auto visit = [&](int q, int qu) {
          if (labels[q] != -1 || !pred.similar(p, q)) return;
          labels[q] = attempt;
          members[count] = q, cols[count] = qu, ++count;
        };
        if (u > 0) visit(p - 1, u - 1);
        if (u + 1 < width) visit(p + 1, u + 1);
        if (p >= width) visit(p - width, u);
        if (p + width < n) visit(p + width, u);
      }
    }
    if (count >= min_size && count <= max_size) {
      ws.remap.push_back(int(out.size()));
      Segment seg;
      seg.indices.resize(std::size_t(count));  // filled in raster order below
      out.push_back(std::move(seg));
    } else {
      ws.remap.push_back(-1);
    }
    ++attempt;
  }
  // One sequential pass: attempt → kept segment id (or -1), and each kept segment's indices in
  // ascending (raster) order, written into the buffers sized above. Branch-free (members and
  // non-members alternate unpredictably): labels -3 / -1 / attempt k map through remap shifted by
  // 3, and a pixel of no segment writes its index to a dummy slot that does not advance.
  ws.remap.insert(ws.remap.begin(), 3, -1);
  const int* remap = ws.remap.data() + 3;
  ws.slots.resize(out.size() + 1);
  int** slots = ws.slots.data();
  int dummy = 0;
  slots[0] = &dummy;
  for (std::size_t k = 0; k < out.size(); ++k) slots[k + 1] = out[k].indices.data();
  for (int i = 0; i < n; ++i) {
    const int l = remap[labels[i]];
    labels[i] = l;
    int*& slot = slots[l + 1];
    *slot = i;
    slot += l >= 0 ? 1 : 0;
  }
  return out;
}

/// summarize() for a segment whose indices are ascending (as flood_fill returns them): the same
/// sums in the same order, with the pixel row tracked instead of divided out.
inline void summarize_raster(Segment& seg, const OrganizedCloud& cloud) {
  if (seg.indices.empty()) {
    summarize(seg, cloud);
    return;
  }
  const int w = cloud.width;
  double sx = 0, sy = 0, sz = 0;
  float lx = std::numeric_limits<float>::max(), ly = lx, lz = lx, hx = -lx, hy = -lx, hz = -lx;
  int u0 = w, u1 = -1;
  int v = seg.indices.front() / w, row_start = v * w;
  const int v0 = v;
  for (int i : seg.indices) {
    while (i >= row_start + w) ++v, row_start += w;
    const float x = cloud.x[std::size_t(i)], y = cloud.y[std::size_t(i)], z = cloud.z[std::size_t(i)];
    sx += double(x), sy += double(y), sz += double(z);
    lx = std::min(lx, x), ly = std::min(ly, y), lz = std::min(lz, z);
    hx = std::max(hx, x), hy = std::max(hy, y), hz = std::max(hz, z);
    const int u = i - row_start;
    u0 = std::min(u0, u), u1 = std::max(u1, u);
  }
  const double k = double(seg.indices.size());
  seg.centroid = Eigen::Vector3f(float(sx / k), float(sy / k), float(sz / k));
  seg.min = Eigen::Vector3f(lx, ly, lz);
  seg.max = Eigen::Vector3f(hx, hy, hz);
  seg.box = {u0, v0, u1 - u0 + 1, v - v0 + 1};
}

/// flood_fill over `cloud`'s grid, then the summary (centroid, bounds, box) of every kept segment.
template <class Pred>
std::vector<Segment> flood_fill_segments(const OrganizedCloud& cloud, const Pred& pred, int min_size, int max_size,
                                         FloodFillWorkspace& ws) {
  auto segs = flood_fill(cloud.width, cloud.height, pred, min_size, max_size, ws);
  for (auto& s : segs) summarize_raster(s, cloud);
  return segs;
}

}  // namespace cropsight::segmentation
