#pragma once
// The command line the broccoli probes share: MODEL.json seq[,seq] [key=value ...]. The detector
// runs the model's recorded configuration (as `eval broccoli --model` does) with the overrides.
#include <cstdio>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cropsight/learning/model.hpp"
#include "cropsight/pipeline/broccoli/detector.hpp"
#include "cropsight/pipeline/broccoli/pipeline.hpp"

namespace cropsight::tools {

struct BroccoliProbeArgs {
  std::shared_ptr<learning::Model> model;
  pipeline::broccoli::DetectorConfig config;
  std::vector<std::string> sequences;
};

/// Parses argv; prints the usage line and returns nothing when arguments are missing.
inline std::optional<BroccoliProbeArgs> parse_probe_args(const char* tool, int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s MODEL.json seq[,seq] [key=value ...]\n", tool);
    return std::nullopt;
  }
  BroccoliProbeArgs a;
  const std::string model_path = argv[1];
  a.model = std::make_shared<learning::Model>(learning::load_model(model_path));
  ConfigMap overrides;
  for (int i = 3; i < argc; ++i) {
    const std::string kv = argv[i];
    const auto eq = kv.find('=');
    overrides[kv.substr(0, eq)] = eq == std::string::npos ? "" : kv.substr(eq + 1);
  }
  a.config = pipeline::broccoli::config_for_model(*a.model, overrides, model_path, "args").detector;
  std::stringstream ss(argv[2]);
  for (std::string dir; std::getline(ss, dir, ',');) a.sequences.push_back(dir);
  return a;
}

/// The clusters a detector leaves unaccepted that the concave-crease split would look at: oversized
/// regions and rejected clusters of detection.split_min_points or more.
inline bool unaccepted_large(const pipeline::broccoli::Candidate& c, const pipeline::broccoli::DetectorConfig& cfg) {
  return !c.head && (c.oversized || int(c.segment.size()) >= cfg.detection.split_min_points);
}

}  // namespace cropsight::tools
