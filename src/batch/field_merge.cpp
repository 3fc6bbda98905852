// Merging field maps by the temporal filter's association rule (batch/field_merge.hpp).
#include "cropsight/batch/field_merge.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>
#include <unordered_map>

namespace cropsight::batch {

namespace {

// A uniform grid over the merged heads (cell = the association radius): the pairs within the
// radius of a point lie in its cell's 3×3×3 neighbourhood.
class HeadGrid {
 public:
  explicit HeadGrid(double cell) : cell_(cell) {}
  void insert(int id, const Eigen::Vector3d& p) { cells_[key(p)].push_back(id); }
  void move(int id, const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
    const auto a = key(from), b = key(to);
    if (a == b) return;
    auto& v = cells_[a];
    v.erase(std::find(v.begin(), v.end(), id));
    cells_[b].push_back(id);
  }
  template <class F>
  void near(const Eigen::Vector3d& p, F&& f) const {
    const auto [x, y, z] = coords(p);
    for (long dx = -1; dx <= 1; ++dx)
      for (long dy = -1; dy <= 1; ++dy)
        for (long dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find(pack(x + dx, y + dy, z + dz));
          if (it != cells_.end())
            for (int id : it->second) f(id);
        }
  }

 private:
  std::tuple<long, long, long> coords(const Eigen::Vector3d& p) const {
    return {long(std::floor(p.x() / cell_)), long(std::floor(p.y() / cell_)), long(std::floor(p.z() / cell_))};
  }
  static std::uint64_t pack(long x, long y, long z) {
    return (std::uint64_t(x & 0x1FFFFF) << 42) | (std::uint64_t(y & 0x1FFFFF) << 21) | std::uint64_t(z & 0x1FFFFF);
  }
  std::uint64_t key(const Eigen::Vector3d& p) const {
    const auto [x, y, z] = coords(p);
    return pack(x, y, z);
  }
  double cell_;
  std::unordered_map<std::uint64_t, std::vector<int>> cells_;
};

struct Pair {
  double d;
  int head, merged;  // index in the map, index in the merged list
};

void absorb(MergedHead& m, const tracking::TrackedHead& h, std::size_t map, const MergeRule& rule) {
  const int n = m.frames_seen + h.frames_seen;
  if (n > 0) m.position = (m.position * m.frames_seen + h.position * h.frames_seen) / double(n);
  m.frames_seen = n;
  if (h.diameter_mm > 0 && h.frames_seen > 0) {
    const double w0 = m.sized_frames, w1 = h.frames_seen, w = w0 + w1;
    m.diameter_mm = (m.diameter_mm * w0 + h.diameter_mm * w1) / w;
    m.bbox_mm = (m.bbox_mm * w0 + h.bbox_mm * w1) / w;
    m.hull_mm = (m.hull_mm * w0 + h.hull_mm * w1) / w;
    m.sized_frames += h.frames_seen;
  }
  m.harvestable = m.sized_frames > 0 && m.diameter_mm >= rule.market_min_mm && m.diameter_mm <= rule.market_max_mm;
  m.seen_by.push_back({map, h.id, h.first_frame, h.last_frame, h.frames_seen});
}

}  // namespace

std::vector<MergedHead> merge_field_maps(const std::vector<PassMap>& maps, const MergeRule& rule) {
  const double r = rule.association_radius_m;
  std::vector<MergedHead> merged;
  HeadGrid grid(r);
  std::vector<Pair> pairs;
  std::vector<char> head_taken, merged_taken;
  for (std::size_t m = 0; m < maps.size(); ++m) {
    const auto& heads = maps[m].heads;
    pairs.clear();
    for (int j = 0; j < int(heads.size()); ++j)
      grid.near(heads[j].position, [&](int k) {
        const double d = (merged[k].position - heads[j].position).norm();
        if (d <= r) pairs.push_back({d, j, k});
      });
    std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) {
      return std::tie(a.d, a.head, a.merged) < std::tie(b.d, b.head, b.merged);
    });
    head_taken.assign(heads.size(), 0);
    merged_taken.assign(merged.size(), 0);
    for (const Pair& p : pairs) {
      if (head_taken[p.head] || merged_taken[p.merged]) continue;
      head_taken[p.head] = merged_taken[p.merged] = 1;
      const Eigen::Vector3d before = merged[p.merged].position;
      absorb(merged[p.merged], heads[p.head], m, rule);
      grid.move(p.merged, before, merged[p.merged].position);
    }
    for (int j = 0; j < int(heads.size()); ++j) {
      if (head_taken[j]) continue;
      MergedHead h;
      h.id = int(merged.size()) + 1;
      absorb(h, heads[j], m, rule);
      grid.insert(int(merged.size()), h.position);
      merged.push_back(std::move(h));
    }
  }
  return merged;
}

void assign_rows(std::vector<MergedHead>& heads, double row_gap_m) {
  std::vector<std::size_t> order(heads.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return heads[a].position.y() < heads[b].position.y(); });
  int row = 0;
  double last_y = 0;
  for (std::size_t i : order) {
    if (row == 0 || heads[i].position.y() - last_y > row_gap_m) ++row;
    heads[i].row = row;
    last_y = heads[i].position.y();
  }
}

}  // namespace cropsight::batch
