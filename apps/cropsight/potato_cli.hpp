#pragma once
// Shared by the potato commands: the pipeline and detector a preset and --set choose, and the JSON
// of the library's potato results.
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "cropsight/core/detection2d.hpp"
#include "cropsight/pipeline/potato/make_pipeline.hpp"
#include "cropsight/pipeline/potato/pipeline.hpp"

namespace cropsight::cli {

/// The pipeline configuration of the "potato" preset (or --config) overlaid with --set and
/// validated; an unknown key or a bad value is an Error naming the preset or "--set".
pipeline::potato::Config potato_config(const CommonOptions& common);

/// The potato pipeline of --config, --set and --model (an ONNX detector; "" = the preset's),
/// built by the library's one builder (pipeline::potato::make_pipeline).
std::unique_ptr<pipeline::potato::Pipeline> make_potato(const CommonOptions& common, const std::string& model = "");

/// The detector that configuration names (detector.backend: classical | onnx).
std::unique_ptr<Detector2D> potato_detector(const CommonOptions& common);

/// One harvest message (paper Table 3.2 and the fields that follow it) as one JSON object.
nlohmann::json harvest_json(const pipeline::potato::HarvestTarget& t);

/// detect potato's boxes of one image: [{class, score, x1, y1, x2, y2[, angle]}], class from
/// `names`, angle (rad, null where none) for each box `angles` covers.
nlohmann::json detections_json(const std::vector<Detection2D>& dets, const std::vector<std::string>& names,
                               const std::vector<std::optional<double>>& angles);

}  // namespace cropsight::cli
