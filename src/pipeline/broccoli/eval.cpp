// Per-frame evaluation of the broccoli pipeline (see eval.hpp).
#include "cropsight/pipeline/broccoli/eval.hpp"

#include "cropsight/core/error.hpp"

namespace cropsight::pipeline::broccoli {

Evaluator::Evaluator(Pipeline& pipeline) : pipeline_(pipeline) {}

void Evaluator::add_frame(const RgbdFrame& frame) {
  require_labels(frame);
  r_.pipeline_ms += pipeline_.process(frame).detect_ms();
  const Detector& det = pipeline_.detector();
  const TruthRules& rules = pipeline_.config().truth;
  const std::span<const Candidate> cands = det.candidates();
  ++r_.frames;
  r_.clusters += long(cands.size());
  std::vector<eval::DetectionApAccumulator::Scored> scored;
  scored.reserve(cands.size());
  for (const Candidate& c : cands) {
    r_.confusion.add(is_head(c.segment.indices, det.cloud().labels, rules.min_head_fraction), c.head);
    r_.detections += c.head;
    scored.push_back({c.score, c.segment.indices});
  }
  // truth_sets_ and small_ (heads under visible_truth_points) from truth_.
  const std::size_t visible = std::size_t(rules.visible_truth_points);
  auto take_truth = [&] {
    truth_sets_.resize(truth_.size());
    small_.resize(truth_.size());
    for (std::size_t i = 0; i < truth_.size(); ++i) {
      truth_sets_[i] = truth_[i].indices;
      small_[i] = truth_[i].indices.size() < visible;
    }
  };
  truth_instances(det.cloud(), rules.min_truth_points, truth_);
  take_truth();
  cut_.resize(truth_.size());
  for (std::size_t i = 0; i < truth_.size(); ++i) cut_[i] = truth_[i].cut_by_border;
  ap_.add_frame(truth_sets_, scored);
  ap_view_.add_frame(truth_sets_, scored, cut_);
  ap_visible_.add_frame(truth_sets_, scored, small_);
  // The same AP over every head the sensor measured, in or out of the depth window.
  truth_instances_any_depth(frame.labels.data, frame.depth.data, frame.depth.width, frame.depth.height,
                            rules.min_truth_points, truth_);
  take_truth();
  ap_any_.add_frame(truth_sets_, scored);
  ap_any_visible_.add_frame(truth_sets_, scored, small_);
}

Figures Evaluator::figures() const {
  Figures r = r_;
  r.truth_heads = ap_.num_truth();
  r.ap50 = ap_.ap(0.5);
  r.map50_95 = ap_.map50_95();
  r.truth_heads_in_view = ap_view_.num_truth();
  r.ap50_in_view = ap_view_.ap(0.5);
  r.map50_95_in_view = ap_view_.map50_95();
  r.truth_heads_visible = ap_visible_.num_truth();
  r.ap50_visible = ap_visible_.ap(0.5);
  r.map50_95_visible = ap_visible_.map50_95();
  r.truth_heads_any_depth = ap_any_.num_truth();
  r.ap50_any_depth = ap_any_.ap(0.5);
  r.truth_heads_visible_any_depth = ap_any_visible_.num_truth();
  r.ap50_visible_any_depth = ap_any_visible_.ap(0.5);
  r.stages = pipeline_.detector().timer().stages();
  return r;
}

}  // namespace cropsight::pipeline::broccoli
