#include "potato_cli.hpp"

#include "cropsight/core/error.hpp"
#include "cropsight/pipeline/potato/potato_blob_detector.hpp"

namespace cropsight::cli {

std::unique_ptr<Detector2D> potato_detector(const CommonOptions& common) {
  ConfigMap m = common.config_map("potato");
  const std::string where = common.sets.empty() ? (common.config.empty() ? "potato" : common.config) : "--config/--set";
  std::string backend = "classical";
  if (auto it = m.find("detector.backend"); it != m.end()) backend = it->second, m.erase(it);
  if (backend != "classical") throw Error(where, "'detector.backend' is '" + backend + "'; this build has: classical");
  for (const auto& [key, value] : m)
    if (key.rfind("detector.classical.", 0) != 0) throw Error(where, "unknown configuration key '" + key + "'");
  pipeline::potato::PotatoBlobConfig cfg;
  apply_config(cfg, m, where, "detector.classical.");
  cfg.validate(where);
  return std::make_unique<pipeline::potato::PotatoBlobDetector>(cfg);
}

}  // namespace cropsight::cli
