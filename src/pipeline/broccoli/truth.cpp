#include "cropsight/pipeline/broccoli/truth.hpp"

#include "cropsight/core/error.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>

namespace cropsight::pipeline::broccoli {

void require_labels(const RgbdFrame& frame) {
  if (frame.labels.empty())
    throw Error("frame " + std::to_string(frame.index), "has no label image (ground truth needed)");
}

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

namespace {
// Point sets of the labelled ids over the pixels `valid(i)` accepts; see truth_instances.
// `labels` holds w·h ids (the callers check it).
template <class Valid>
void collect_instances(std::span<const std::uint16_t> labels, int w, int h, int min_points, Valid valid,
                       std::vector<TruthInstance>& out) {
  for (auto& inst : out) inst.indices.clear();
  std::size_t used = 0;
  // Ids are sparse (1..65535): map id → slot through a sorted list of the ids seen.
  std::vector<std::pair<int, std::size_t>> slot_of;
  const int n = w * h;
  for (int i = 0; i < n; ++i) {
    const int id = labels[std::size_t(i)];
    if (id == 0 || !valid(std::size_t(i))) continue;
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
  auto border = [&](int i) {
    const int id = labels[std::size_t(i)];
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
}  // namespace

void truth_instances(const OrganizedCloud& cloud, int min_points, std::vector<TruthInstance>& out) {
  if (!cloud.has_labels()) {
    out.resize(0);
    return;
  }
  collect_instances(
      cloud.labels, cloud.width, cloud.height, min_points, [&](std::size_t i) { return cloud.valid(i); }, out);
}

void truth_instances_any_depth(std::span<const std::uint16_t> labels, std::span<const std::uint16_t> depth, int width,
                               int height, int min_points, std::vector<TruthInstance>& out) {
  const std::size_t n = std::size_t(std::max(0, width)) * std::size_t(std::max(0, height));
  if (labels.empty()) {
    out.resize(0);
    return;
  }
  if (labels.size() != n || depth.size() != n)
    throw std::invalid_argument("truth_instances_any_depth: label and depth images must hold width x height pixels");
  collect_instances(
      labels, width, height, min_points, [&](std::size_t i) { return depth[i] != 0; }, out);
}

}  // namespace cropsight::pipeline::broccoli
