#include "cropsight/pipeline/broccoli/broccoli_truth.hpp"

#include <algorithm>
#include <array>

namespace cropsight::pipeline {

ClusterTruth cluster_truth(std::span<const int> indices, std::span<const std::uint16_t> labels, float min_fraction) {
  if (labels.empty() || indices.empty()) return {};
  // A cluster touches few heads: count ids in a small linear table (no allocation).
  std::array<std::pair<std::uint16_t, int>, 16> counts{};
  std::size_t used = 0;
  int overflow = 0;
  for (int i : indices) {
    const std::uint16_t id = labels[std::size_t(i)];
    if (id == 0) continue;
    std::size_t k = 0;
    while (k < used && counts[k].first != id) ++k;
    if (k == used) {
      if (used == counts.size()) {
        ++overflow;  // a 17th distinct id: cannot hold half of the points anyway unless tiny
        continue;
      }
      counts[used++] = {id, 0};
    }
    ++counts[k].second;
  }
  ClusterTruth t;
  int best = 0;
  for (std::size_t k = 0; k < used; ++k)
    if (counts[k].second > best) best = counts[k].second, t.head_id = counts[k].first;
  t.fraction = float(best) / float(indices.size());
  if (t.fraction < min_fraction) t.head_id = 0;
  return t;
}

void truth_instances(const OrganizedCloud& cloud, int min_points, std::vector<TruthInstance>& out) {
  for (auto& inst : out) inst.indices.clear();
  std::size_t used = 0;
  if (!cloud.has_labels()) {
    out.resize(0);
    return;
  }
  // Ids are sparse (1..65535): map id → slot through a sorted list of the ids seen.
  std::vector<std::pair<int, std::size_t>> slot_of;
  const int n = int(cloud.size());
  for (int i = 0; i < n; ++i) {
    const int id = cloud.labels[std::size_t(i)];
    if (id == 0 || !cloud.valid(std::size_t(i))) continue;
    auto it = std::lower_bound(slot_of.begin(), slot_of.end(), std::make_pair(id, std::size_t(0)));
    std::size_t slot;
    if (it != slot_of.end() && it->first == id) {
      slot = it->second;
    } else {
      slot = used++;
      slot_of.insert(it, {id, slot});
      if (out.size() < used) out.emplace_back();
      out[slot].id = id;
      out[slot].indices.clear();
    }
    out[slot].indices.push_back(i);  // raster order: ascending
  }
  // Heads with a labelled pixel on the image border continue outside the view.
  std::vector<int> border_ids;
  const int w = cloud.width, h = cloud.height;
  auto border = [&](int i) {
    const int id = cloud.labels[std::size_t(i)];
    if (id != 0) border_ids.push_back(id);
  };
  for (int u = 0; u < w; ++u) border(u), border((h - 1) * w + u);
  for (int v = 0; v < h; ++v) border(v * w), border(v * w + w - 1);
  std::sort(border_ids.begin(), border_ids.end());
  for (const auto& [id, slot] : slot_of)
    out[slot].cut_by_border = std::binary_search(border_ids.begin(), border_ids.end(), id);
  // Order by id and drop heads that are too small to count.
  std::vector<TruthInstance> kept;
  kept.reserve(used);
  for (const auto& [id, slot] : slot_of)
    if (int(out[slot].indices.size()) >= std::max(1, min_points)) kept.push_back(std::move(out[slot]));
  out = std::move(kept);
}

}  // namespace cropsight::pipeline
