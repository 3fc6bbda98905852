#pragma once
// Described candidates → scores and decisions, the broccoli detector's classify step (StageTimer
// "classify"): the model's score (SVM decision value / KNN vote; score units) of every described
// candidate, scored together in one batch (learning::Model::score_rows: the same scores as one
// by one, the support vectors read once per block); a head is a score above the model's
// threshold plus detection.score_margin. A candidate that is not described gets the lowest score
// and is never a head. Without a model every described candidate scores 0 and none is a head.
// The batch buffers are reused from frame to frame.
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "cropsight/core/timer.hpp"
#include "cropsight/learning/model.hpp"
#include "cropsight/pipeline/broccoli/candidate.hpp"

namespace cropsight::pipeline::broccoli::steps {

class ClassificationStep {
 public:
  explicit ClassificationStep(float score_margin) : score_margin_(score_margin) {}

  /// The caller checks that the model suits the features (Detector::set_model); null = none.
  void set_model(std::shared_ptr<const learning::Model> model) { model_ = std::move(model); }
  const std::shared_ptr<const learning::Model>& model() const { return model_; }
  bool has_model() const { return model_ != nullptr; }
  /// The score a head must exceed: the model's threshold + score_margin (0 without a model).
  float head_threshold() const { return model_ ? model_->threshold() + score_margin_ : 0.0f; }

  /// Scores every candidate of `pool` against head_threshold().
  void run(CandidatePool& pool, StageTimer& timer);
  /// Scores `cands` together; each is a head when its score exceeds `threshold`.
  void classify(std::span<Candidate* const> cands, float threshold);
  /// The same for one candidate.
  void classify(Candidate& c, float threshold);

 private:
  float score_margin_;
  std::shared_ptr<const learning::Model> model_;
  std::vector<Candidate*> all_, batch_;  // run()'s input; the described ones, scored together
  std::vector<float> rows_, scores_, scratch_;
};

}  // namespace cropsight::pipeline::broccoli::steps
