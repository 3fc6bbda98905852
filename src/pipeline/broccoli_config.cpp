#include "cropsight/pipeline/broccoli_config.hpp"

#include <sstream>

#include "cropsight/core/error.hpp"

namespace cropsight::pipeline {

void BroccoliDetectorConfig::validate(const std::string& where) const {
  if (pipeline != "oes" && pipeline != "org" && pipeline != "fec")
    throw Error(where, "pipeline must be oes, org or fec, got '" + pipeline + "'");
  features::FeatureSet::parse(features, where);
  classifier.validate(where);
  depth.validate();
  if (!(detection.min_head_fraction > 0.0f && detection.min_head_fraction <= 1.0f))
    throw Error(where, "detection.min_head_fraction must be in (0, 1]");
  if (detection.min_truth_points < 0) throw Error(where, "detection.min_truth_points must be >= 0");
  if (detection.visible_truth_points < 0) throw Error(where, "detection.visible_truth_points must be >= 0");
  if (detection.min_normal_points < 0) throw Error(where, "detection.min_normal_points must be >= 0");
}

std::vector<std::string> BroccoliDetectorConfig::feature_names() const {
  std::vector<std::string> out;
  std::istringstream in(features::FeatureSet::parse(features, "features").spec());
  for (std::string part; std::getline(in, part, ',');) out.push_back(part);
  return out;
}

}  // namespace cropsight::pipeline
