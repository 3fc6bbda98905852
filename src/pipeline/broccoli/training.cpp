#include "cropsight/pipeline/broccoli/training.hpp"

#include "cropsight/core/config.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/pipeline/broccoli/truth.hpp"

namespace cropsight::pipeline::broccoli {

namespace {

/// The detector that builds training samples: the config, without denoising unless in_training,
/// and without the head CNN (its proposals have no features, and the clusters it carves would keep
/// the features of their whole): the classifier learns from the clustering's candidates alone.
DetectorConfig training_detector(DetectorConfig cfg) {
  if (!cfg.denoise.in_training) cfg.denoise.above = 0.0f;
  cfg.cnn.model.clear();
  return cfg;
}
}  // namespace

DatasetBuilder::DatasetBuilder(const DetectorConfig& cfg, const TruthRules& truth)
    : detector_(training_detector(cfg)), truth_(truth), data_(int(detector_.feature_dimension())) {
  truth_.validate("config");
}

void DatasetBuilder::add_frame(const RgbdFrame& frame) {
  require_labels(frame);
  for (const Candidate& c : detector_.process(frame))
    if (c.described)  // clusters without a shape descriptor are never heads (detection.min_normal_points)
      data_.add(c.features, is_head(c.segment.indices, detector_.cloud().labels, truth_.min_head_fraction) ? 1 : 0,
                "frame " + std::to_string(frame.index));
  ++frames_;
}

ConfigMap config_map(const DetectorConfig& cfg, const TruthRules& truth) {
  ConfigMap m;
  for (const auto& [key, value, doc] : dump_config(cfg)) m[key] = value;
  for (const auto& [key, value, doc] : dump_config(truth, "detection.")) m[key] = value;
  return m;
}

learning::Model train_model(const learning::Dataset& data, const DetectorConfig& cfg, const TruthRules& truth,
                            std::map<std::string, std::string> provenance) {
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

}  // namespace cropsight::pipeline::broccoli
