#include "cropsight/segmentation/segment_growth.hpp"

#include <algorithm>
#include <string>

#include "cropsight/core/error.hpp"

namespace cropsight::segmentation {

std::size_t grow_into_free_pixels(const OrganizedCloud& cloud, std::span<Segment* const> segments,
                                  std::span<const int> grow, const SegmentGrowthOptions& options,
                                  SegmentGrowthWorkspace& ws) {
  if (grow.empty()) return 0;
  const int n = int(cloud.z.size());
  ws.owner.assign(std::size_t(n), -1);
  for (std::size_t k = 0; k < segments.size(); ++k)
    for (int i : segments[k]->indices) {
      if (i < 0 || i >= n)
        throw Error("segment growth", "segment index " + std::to_string(i) + " lies outside the cloud");
      ws.owner[std::size_t(i)] = int(k);
    }
  return grow_into_free_pixels(cloud, segments, grow, options, ws.owner, ws.queue);
}

std::size_t grow_into_free_pixels(const OrganizedCloud& cloud, std::span<Segment* const> segments,
                                  std::span<const int> grow, const SegmentGrowthOptions& options, std::span<int> owner,
                                  std::vector<int>& queue) {
  if (grow.empty()) return 0;
  if (!(options.tolerance > 0.0f) || !(options.radius > 0.0f))
    throw Error("segment growth", "tolerance and radius must be positive");
  const int w = cloud.width, n = cloud.width * cloud.height;
  if (cloud.z.size() != std::size_t(n) || owner.size() != std::size_t(n))
    throw Error("segment growth", "cloud or owner map is not width x height");
  const float tol2 = options.tolerance * options.tolerance, r2 = options.radius * options.radius;
  const float* x = cloud.x.data();
  const float* y = cloud.y.data();
  const float* z = cloud.z.data();
  std::size_t added_total = 0;
  for (int k : grow) {
    if (k < 0 || std::size_t(k) >= segments.size())
      throw Error("segment growth", "segment " + std::to_string(k) + " does not exist");
    Segment& s = *segments[std::size_t(k)];
    if (s.indices.empty()) continue;
    const float cx = s.centroid.x(), cy = s.centroid.y(), cz = s.centroid.z();
    // Breadth-first from every pixel of the segment; the queue ends up holding the segment's
    // pixels followed by the grown ones.
    queue.assign(s.indices.begin(), s.indices.end());
    for (int i : s.indices)
      if (i < 0 || i >= n)
        throw Error("segment growth", "segment index " + std::to_string(i) + " lies outside the cloud");
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const int p = queue[head];
      const int u = p % w;
      const int nb[4] = {u + 1 < w ? p + 1 : -1, u > 0 ? p - 1 : -1, p + w < n ? p + w : -1, p - w};
      for (int q : nb) {
        if (q < 0 || owner[std::size_t(q)] != -1) continue;
        // Written as "not within" so that a NaN point (an invalid pixel) never joins.
        const float dx = x[q] - x[p], dy = y[q] - y[p], dz = z[q] - z[p];
        if (!(dx * dx + dy * dy + dz * dz < tol2)) continue;
        const float ex = x[q] - cx, ey = y[q] - cy, ez = z[q] - cz;
        if (!(ex * ex + ey * ey + ez * ez < r2)) continue;
        owner[std::size_t(q)] = k;
        queue.push_back(q);
      }
    }
    const std::size_t added = queue.size() - s.indices.size();
    if (added == 0) continue;
    added_total += added;
    s.indices.assign(queue.begin(), queue.end());
    std::sort(s.indices.begin(), s.indices.end());
    summarize(s, cloud);
  }
  return added_total;
}

}  // namespace cropsight::segmentation
