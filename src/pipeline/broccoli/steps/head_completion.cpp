#include "cropsight/pipeline/broccoli/steps/head_completion.hpp"

#include <algorithm>

namespace cropsight::pipeline::broccoli::steps {

void HeadCompletion::refine(const RgbdFrame&, FrameState& state, StageTimer& timer) {
  auto t = timer.scope("completion");
  CandidatePool& pool = state.candidates;
  grow_order_.clear();
  segments_.clear();
  for (std::size_t k = 0; k < pool.size(); ++k) {
    segments_.push_back(&pool[k].segment);
    if (pool[k].head) grow_order_.push_back(int(k));
  }
  if (grow_order_.empty()) return;
  // The most confident head claims contested debris first.
  std::stable_sort(grow_order_.begin(), grow_order_.end(),
                   [&](int a, int b) { return pool[std::size_t(a)].score > pool[std::size_t(b)].score; });
  // The organised clusterings' label image is already the owner map (segment k = candidate k).
  if (state.owners.empty())
    segmentation::grow_into_free_pixels(state.cloud, segments_, grow_order_, options_, growth_);
  else
    segmentation::grow_into_free_pixels(state.cloud, segments_, grow_order_, options_, state.owners, growth_.queue);
}

}  // namespace cropsight::pipeline::broccoli::steps
