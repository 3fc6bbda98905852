#pragma once
// Shared by the potato commands (issue 22): the detector a preset and --set choose.
#include <memory>

#include "cli_common.hpp"
#include "cropsight/core/detection2d.hpp"

namespace cropsight::cli {

/// The detector of the "potato" preset (or --config) overlaid with --set: `detector.backend`
/// (only "classical" in this build) and `detector.classical.*` (PotatoBlobConfig). Any other key
/// is an Error naming the preset or "--set".
std::unique_ptr<Detector2D> potato_detector(const CommonOptions& common);

}  // namespace cropsight::cli
