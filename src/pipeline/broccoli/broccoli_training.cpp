#include "cropsight/pipeline/broccoli/broccoli_training.hpp"

#include "cropsight/core/config.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/pipeline/broccoli/broccoli_truth.hpp"

namespace cropsight::pipeline {

namespace {
void require_labels(const RgbdFrame& frame) {
  if (frame.labels.empty())
    throw Error("frame " + std::to_string(frame.index), "has no label image (ground truth needed)");
}

/// The cluster rule of broccoli_truth.hpp on the cloud's labels.
bool is_head(const BroccoliCandidate& c, const OrganizedCloud& cloud, const BroccoliTruthRules& truth) {
  return cluster_truth(c.segment.indices, cloud.labels, truth.min_head_fraction).head_id != 0;
}
/// The detector that builds training samples: the config, without denoising unless in_training,
/// and without the head CNN (its proposals have no features, and the clusters it carves would keep
/// the features of their whole): the classifier learns from the clustering's candidates alone.
BroccoliDetectorConfig training_detector(BroccoliDetectorConfig cfg) {
  if (!cfg.denoise.in_training) cfg.denoise.above = 0.0f;
  cfg.cnn.model.clear();
  return cfg;
}
}  // namespace

BroccoliDatasetBuilder::BroccoliDatasetBuilder(const BroccoliDetectorConfig& cfg, const BroccoliTruthRules& truth)
    : detector_(training_detector(cfg)), truth_(truth), data_(int(detector_.feature_dimension())) {
  truth_.validate("config");
}

void BroccoliDatasetBuilder::add_frame(const RgbdFrame& frame) {
  require_labels(frame);
  for (const BroccoliCandidate& c : detector_.process(frame))
    if (c.described)  // clusters without a shape descriptor are never heads (detection.min_normal_points)
      data_.add(c.features, is_head(c, detector_.cloud(), truth_) ? 1 : 0, "frame " + std::to_string(frame.index));
  ++frames_;
}

ConfigMap config_map(const BroccoliDetectorConfig& cfg, const BroccoliTruthRules& truth) {
  ConfigMap m;
  for (const auto& [key, value, doc] : dump_config(cfg)) m[key] = value;
  for (const auto& [key, value, doc] : dump_config(truth, "detection.")) m[key] = value;
  return m;
}

learning::Model train_broccoli_model(const learning::Dataset& data, const BroccoliDetectorConfig& cfg,
                                     const BroccoliTruthRules& truth, std::map<std::string, std::string> provenance) {
  cfg.validate("config");
  truth.validate("config");
  learning::ModelInfo info;
  info.task = kBroccoliTask;
  info.pipeline = config_name(cfg.pipeline);
  info.features = cfg.feature_names();
  info.config = config_map(cfg, truth);
  provenance["samples"] = std::to_string(data.size());
  provenance["positives"] = std::to_string(data.positives());
  info.provenance = std::move(provenance);
  return learning::train_model(data, cfg.classifier, std::move(info));
}

BroccoliEvaluator::BroccoliEvaluator(BroccoliPipeline& pipeline) : pipeline_(pipeline) {}

void BroccoliEvaluator::add_frame(const RgbdFrame& frame) {
  require_labels(frame);
  r_.pipeline_ms += pipeline_.process(frame).detect_ms;
  const BroccoliDetector& det = pipeline_.detector();
  const BroccoliTruthRules& rules = pipeline_.config().truth;
  const std::span<const BroccoliCandidate> cands = det.candidates();
  ++r_.frames;
  r_.clusters += long(cands.size());
  std::vector<eval::DetectionApAccumulator::Scored> scored;
  scored.reserve(cands.size());
  for (const BroccoliCandidate& c : cands) {
    r_.confusion.add(is_head(c, det.cloud(), rules), c.head);
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
  r.truth_heads_any_depth = ap_any_.num_truth();
  r.ap50_any_depth = ap_any_.ap(0.5);
  r.truth_heads_visible_any_depth = ap_any_visible_.num_truth();
  r.ap50_visible_any_depth = ap_any_visible_.ap(0.5);
  r.stages = pipeline_.detector().timer().stages();
  return r;
}

}  // namespace cropsight::pipeline
