#include "cropsight/pipeline/broccoli/steps/classification_step.hpp"

#include <limits>

namespace cropsight::pipeline::broccoli::steps {

void ClassificationStep::run(CandidatePool& pool, StageTimer& timer) {
  auto t = timer.scope("classify");
  all_.clear();
  for (Candidate& c : pool.active()) all_.push_back(&c);
  classify(all_, head_threshold());
}

void ClassificationStep::classify(std::span<Candidate* const> cands, float threshold) {
  batch_.clear();
  rows_.clear();
  for (Candidate* c : cands) {
    if (!model_ || !c->described) {
      classify(*c, threshold);
      continue;
    }
    batch_.push_back(c);
    rows_.insert(rows_.end(), c->features.begin(), c->features.end());
  }
  if (batch_.empty()) return;
  scores_.resize(batch_.size());
  model_->score_rows(rows_, scores_, scratch_);
  for (std::size_t k = 0; k < batch_.size(); ++k) {
    batch_[k]->score = scores_[k];
    batch_[k]->head = scores_[k] > threshold;
  }
}

void ClassificationStep::classify(Candidate& c, float threshold) {
  // A cluster without normals has an all-zero VFH, the same vector for every such sliver: an
  // RBF SVM answers it with whatever its nearest support vector says (measured: 1.0, a head).
  if (!c.described) {
    c.score = -std::numeric_limits<float>::max();
    c.head = false;
    return;
  }
  c.score = model_ ? model_->score(c.features, scratch_) : 0.0f;
  c.head = model_ && c.score > threshold;
}

}  // namespace cropsight::pipeline::broccoli::steps
