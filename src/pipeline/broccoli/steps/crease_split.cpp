#include "cropsight/pipeline/broccoli/steps/crease_split.hpp"

#include <cmath>
#include <utility>

#include "cropsight/geometry/concave_creases.hpp"

namespace cropsight::pipeline::broccoli::steps {

void CreaseSplit::refine(const RgbdFrame&, FrameState& state, StageTimer& timer) {
  if (!classification_.has_model()) return;
  auto t = timer.scope("split");
  const float head = classification_.head_threshold();
  mark_targets(state, head);
  if (targets_.empty()) return;
  const segmentation::OesConfig& oes = state.conditions.oes;
  std::vector<segmentation::SplitPiece> split = segmentation::split_segments(
      state.cloud, segments_, targets_, creases_, oes.distance_tolerance, oes.min_size, oes.max_size, split_ws_);
  // Pieces cut from leaves are more often taken for heads than whole clusters: a higher bar.
  const float threshold = head + cfg_.split_score_margin;
  score_pieces(split, state, threshold);
  replace_parents(split, state, threshold);
}

void CreaseSplit::mark_targets(const FrameState& state, float head_threshold) {
  targets_.clear();
  segments_.clear();
  creases_.assign(state.cloud.size(), 0);
  const geometry::ConcaveCreaseOptions creases{cfg_.split_concave_angle_deg, cfg_.split_concave_step};
  const CandidatePool& pool = state.candidates;
  for (std::size_t k = 0; k < pool.size(); ++k) {
    const Candidate& c = pool[k];
    segments_.push_back(&c.segment);
    if (!c.oversized) {
      if (!c.described || int(c.segment.size()) < cfg_.split_min_points) continue;
      if (c.head && !cfg_.split_accepted) continue;
      // Only scores near the threshold: a head joined to a leaf scores between a leaf and a head.
      if (cfg_.split_score_window > 0.0f && std::fabs(c.score - head_threshold) > cfg_.split_score_window) continue;
    }
    targets_.push_back(int(k));
    geometry::mark_concave_creases(state.cloud, c.segment.indices, creases, creases_);
  }
}

// A piece that keeps most of its cluster (all of it: no crease) is that cluster again, which is
// no head: it is not classified (saves most of the stage's time).
void CreaseSplit::score_pieces(std::vector<segmentation::SplitPiece>& split, const FrameState& state, float threshold) {
  if (pieces_.size() < split.size()) pieces_.resize(split.size());
  scored_.assign(split.size(), 0);
  batch_.clear();
  for (std::size_t i = 0; i < split.size(); ++i) {
    Candidate& piece = pieces_[i];
    const Candidate& parent = state.candidates[std::size_t(split[i].parent)];
    std::swap(piece.segment, split[i].segment);
    piece.oversized = piece.proposed = false;  // the slot may hold a candidate of an earlier frame
    if (double(piece.segment.size()) > double(cfg_.split_max_piece_fraction) * double(parent.segment.size())) continue;
    description_.describe(state.cloud, piece);
    batch_.push_back(&piece);
    scored_[i] = 1;
  }
  classification_.classify(batch_, threshold);
}

void CreaseSplit::replace_parents(const std::vector<segmentation::SplitPiece>& split, FrameState& state,
                                  float threshold) {
  CandidatePool& pool = state.candidates;
  replace_.assign(pool.size(), kKeep);
  // A head cluster (split_accepted) gives way only to a piece that is more head-like than itself.
  for (std::size_t i = 0; i < split.size(); ++i) {
    const Candidate& parent = pool[std::size_t(split[i].parent)];
    if (scored_[i] && pieces_[i].head && (!parent.head || pieces_[i].score > parent.score))
      replace_[std::size_t(split[i].parent)] = kReplace;
  }
  // The replaced cluster's pixels are freed in the owner image (the completion reads it), then the
  // pieces take theirs: the first piece takes the cluster's slot, the others are appended.
  for (std::size_t k = 0; k < replace_.size(); ++k)
    if (replace_[k] == kReplace)
      for (int i : pool[k].segment.indices) state.owners[std::size_t(i)] = -1;
  for (std::size_t i = 0; i < split.size(); ++i) {
    const std::size_t parent = std::size_t(split[i].parent);
    if (replace_[parent] == kKeep) continue;
    if (!scored_[i]) {  // the large remainder beside a head piece (rare): scored now
      description_.describe(state.cloud, pieces_[i]);
      classification_.classify(pieces_[i], threshold);
    }
    std::size_t at = parent;
    if (replace_[parent] == kReplace) {
      replace_[parent] = kSlotTaken;
    } else {
      at = pool.size();
      pool.append();
    }
    std::swap(pool[at], pieces_[i]);
    for (int idx : pool[at].segment.indices) state.owners[std::size_t(idx)] = int(at);
  }
}

}  // namespace cropsight::pipeline::broccoli::steps
