#include "cropsight/pipeline/broccoli_training.hpp"

#include <chrono>

#include "cropsight/core/config.hpp"
#include "cropsight/core/error.hpp"

namespace cropsight::pipeline {

namespace {
void require_labels(const RgbdFrame& frame) {
  if (frame.labels.empty())
    throw Error("frame " + std::to_string(frame.index), "has no label image (ground truth needed)");
}
}  // namespace

BroccoliDatasetBuilder::BroccoliDatasetBuilder(const BroccoliDetectorConfig& cfg)
    : detector_(cfg), data_(int(detector_.feature_dimension())) {}

void BroccoliDatasetBuilder::add_frame(const RgbdFrame& frame) {
  require_labels(frame);
  for (const BroccoliCandidate& c : detector_.process(frame))
    if (c.described)  // clusters without a shape descriptor are never heads (detection.min_normal_points)
      data_.add(c.features, c.truth.head_id != 0 ? 1 : 0, "frame " + std::to_string(frame.index));
  ++frames_;
}

ConfigMap config_map(const BroccoliDetectorConfig& cfg) {
  ConfigMap m;
  for (const auto& [key, value, doc] : dump_config(cfg)) m[key] = value;
  return m;
}

learning::Model train_broccoli_model(const learning::Dataset& data, const BroccoliDetectorConfig& cfg,
                                     std::map<std::string, std::string> provenance) {
  cfg.validate("config");
  learning::ModelInfo info;
  info.task = kBroccoliTask;
  info.pipeline = cfg.pipeline;
  info.features = cfg.feature_names();
  info.config = config_map(cfg);
  provenance["samples"] = std::to_string(data.size());
  provenance["positives"] = std::to_string(data.positives());
  info.provenance = std::move(provenance);
  return learning::train_model(data, cfg.classifier, std::move(info));
}

BroccoliDetectorConfig config_for_model(const learning::Model& model, const ConfigMap& overrides,
                                        const std::string& where) {
  BroccoliDetectorConfig cfg;
  apply_config(cfg, model.info.config, where);
  apply_config(cfg, overrides, "--config/--set");
  cfg.validate(where);
  return cfg;
}

BroccoliEvaluator::BroccoliEvaluator(BroccoliDetector& detector) : det_(detector) {}

void BroccoliEvaluator::add_frame(const RgbdFrame& frame) {
  require_labels(frame);
  const auto t0 = std::chrono::steady_clock::now();
  const std::span<const BroccoliCandidate> cands = det_.process(frame);
  r_.pipeline_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  ++r_.frames;
  r_.clusters += long(cands.size());
  std::vector<eval::DetectionApAccumulator::Scored> scored;
  scored.reserve(cands.size());
  for (const BroccoliCandidate& c : cands) {
    r_.confusion.add(c.truth.head_id != 0, c.head);
    r_.detections += c.head;
    scored.push_back({c.score, c.segment.indices});
  }
  truth_instances(det_.cloud(), det_.config().detection.min_truth_points, truth_);
  truth_sets_.resize(truth_.size());
  cut_.resize(truth_.size());
  small_.resize(truth_.size());
  const std::size_t visible = std::size_t(det_.config().detection.visible_truth_points);
  for (std::size_t i = 0; i < truth_.size(); ++i) {
    truth_sets_[i] = truth_[i].indices;
    cut_[i] = truth_[i].cut_by_border;
    small_[i] = truth_[i].indices.size() < visible;
  }
  ap_.add_frame(truth_sets_, scored);
  ap_view_.add_frame(truth_sets_, scored, cut_);
  ap_visible_.add_frame(truth_sets_, scored, small_);
}

BroccoliEvalResult BroccoliEvaluator::result() const {
  BroccoliEvalResult r = r_;
  r.truth_heads = ap_.num_truth();
  r.ap50 = ap_.ap(0.5);
  r.map50_95 = ap_.map50_95();
  r.truth_heads_in_view = ap_view_.num_truth();
  r.ap50_in_view = ap_view_.ap(0.5);
  r.map50_95_in_view = ap_view_.map50_95();
  r.truth_heads_visible = ap_visible_.num_truth();
  r.ap50_visible = ap_visible_.ap(0.5);
  r.map50_95_visible = ap_visible_.map50_95();
  r.stages = det_.timer().stages();
  return r;
}

}  // namespace cropsight::pipeline
