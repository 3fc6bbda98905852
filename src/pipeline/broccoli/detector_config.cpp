#include "cropsight/pipeline/broccoli/detector_config.hpp"

#include <sstream>

#include "cropsight/core/error.hpp"

namespace cropsight::pipeline::broccoli {

void DetectorConfig::validate(const std::string& where) const {
  features::FeatureSet::parse(features, where);
  classifier.validate(where);
  check_config(*this, where);  // the ranges declared in visit(), naming `where` (the file or --set)
  depth.validate();            // min <= max
  // The split reads OES's label image and tolerance: say so rather than ignore the key.
  if (detection.split_concave_angle_deg > 0.0f && pipeline != Variant::oes)
    throw Error(where, "detection.split_concave_angle_deg needs pipeline oes (0 = off for org and fec)");
}

void TruthRules::validate(const std::string& where) const { check_config(*this, where, "detection."); }

std::vector<std::string> DetectorConfig::feature_names() const {
  std::vector<std::string> out;
  std::istringstream in(features::FeatureSet::parse(features, "features").spec());
  for (std::string part; std::getline(in, part, ',');) out.push_back(part);
  return out;
}

}  // namespace cropsight::pipeline::broccoli
