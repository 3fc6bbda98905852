#include "cropsight/segmentation/segment_split.hpp"

#include <algorithm>

#include "cropsight/core/error.hpp"
#include "cropsight/segmentation/flood_fill.hpp"            // summarize_raster
#include "cropsight/segmentation/organized_clustering.hpp"  // within_tolerance

namespace cropsight::segmentation {

std::vector<SplitPiece> split_segments(const OrganizedCloud& cloud, std::span<const Segment* const> segments,
                                       std::span<const int> targets, std::span<const std::uint8_t> barrier,
                                       float tolerance, int min_size, int max_size, SegmentSplitWorkspace& ws) {
  if (barrier.size() != cloud.size()) throw Error("segment split", "barrier must hold one entry per pixel");
  if (!(tolerance > 0.0f)) throw Error("segment split", "tolerance must be > 0");
  if (min_size < 1 || max_size < min_size)
    throw Error("segment split", "size range must satisfy 1 <= min_size <= max_size");
  for (int t : targets) {
    if (t < 0 || std::size_t(t) >= segments.size()) throw Error("segment split", "target outside the segments");
    for (int i : segments[std::size_t(t)]->indices)
      if (i < 0 || std::size_t(i) >= cloud.size()) throw Error("segment split", "segment index outside the cloud");
  }
  // Only the targets' pixels are visited (a flood over the whole image cost more than the rest of
  // the split): `owner` is -1 everywhere between calls. A target's unmarked pixels hold its index
  // until a fill attempt a takes them (-3 - a); one pass over the target's ascending indices then
  // hands the pixels of the kept attempts to their pieces, in raster order without a sort.
  const int w = cloud.width, n = int(cloud.size());
  ws.owner.resize(cloud.size(), -1);
  int* owner = ws.owner.data();
  for (int t : targets)
    for (int i : segments[std::size_t(t)]->indices)
      if (!barrier[std::size_t(i)] && std::isfinite(cloud.z[std::size_t(i)])) owner[i] = t;
  const float *X = cloud.x.data(), *Y = cloud.y.data(), *Z = cloud.z.data();
  const float tol2 = tolerance * tolerance;
  std::vector<SplitPiece> out;
  std::vector<int>& queue = ws.members;
  std::vector<int>& remap = ws.remap;  // attempt -> index into out, or -1
  for (int t : targets) {
    const std::vector<int>& pixels = segments[std::size_t(t)]->indices;
    remap.clear();
    for (int s : pixels) {
      if (owner[s] != t) continue;
      // Breadth-first over the 4-neighbours of the same target within the tolerance.
      const int code = -3 - int(remap.size());
      // The queue holds (pixel, column) pairs: no division per pixel.
      queue.clear();
      queue.push_back(s);
      queue.push_back(s % w);
      owner[s] = code;
      for (std::size_t head = 0; head < queue.size(); head += 2) {
        const int p = queue[head], u = queue[head + 1];
        auto visit = [&](int q, int qu) {
          if (owner[q] != t || !within_tolerance(X[p] - X[q], Y[p] - Y[q], Z[p] - Z[q], tol2)) return;
          owner[q] = code;
          queue.push_back(q);
          queue.push_back(qu);
        };
        if (u > 0) visit(p - 1, u - 1);
        if (u + 1 < w) visit(p + 1, u + 1);
        if (p >= w) visit(p - w, u);
        if (p + w < n) visit(p + w, u);
      }
      const int size = int(queue.size() / 2);
      if (size < min_size || size > max_size) {
        remap.push_back(-1);
        continue;
      }
      remap.push_back(int(out.size()));
      SplitPiece piece;
      piece.parent = t;
      piece.segment.indices.reserve(std::size_t(size));
      out.push_back(std::move(piece));
    }
    for (int i : pixels) {
      const int code = owner[i];
      if (code <= -3 && remap[std::size_t(-3 - code)] >= 0)
        out[std::size_t(remap[std::size_t(-3 - code)])].segment.indices.push_back(i);
    }
  }
  for (SplitPiece& piece : out) summarize_raster(piece.segment, cloud);  // indices ascending
  for (int t : targets)
    for (int i : segments[std::size_t(t)]->indices) owner[i] = -1;
  // Raster order of the first pixel, as the clusterings return their segments.
  std::sort(out.begin(), out.end(), [](const SplitPiece& a, const SplitPiece& b) {
    return a.segment.indices.front() < b.segment.indices.front();
  });
  return out;
}

}  // namespace cropsight::segmentation
