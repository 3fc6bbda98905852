#pragma once
// Shared by the seedling sub-commands (detect / eval / simulate seedling): configuration loading
// and the JSON form of a detection.
#include <nlohmann/json.hpp>
#include <string>

#include "cli_common.hpp"
#include "cropsight/stereo/seedling_detector.hpp"

namespace cropsight::cli {

/// SeedlingConfig from the preset (default configs/seedling.yaml) and --set overrides.
stereo::SeedlingConfig seedling_config(const CommonOptions& o);
/// found, envelope, plane, point counts, timings in ms per stage.
nlohmann::json seedling_json(const stereo::SeedlingDetection& d);

}  // namespace cropsight::cli
