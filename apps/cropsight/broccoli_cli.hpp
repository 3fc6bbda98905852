#pragma once
// Helpers shared by the broccoli sub-commands (train / detect / eval / bench broccoli).
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cropsight/core/timer.hpp"
#include "cropsight/learning/model.hpp"
#include "cropsight/pipeline/broccoli_training.hpp"

namespace cropsight::cli {

/// "a,b,c" → {"a", "b", "c"}; throws Error(option, ...) when empty or a part is empty.
std::vector<std::string> split_list(const std::string& text, const std::string& option);

/// Loads a model file for the broccoli detector; throws Error(path, ...) when it is missing,
/// malformed or was trained for another task.
std::shared_ptr<const learning::Model> load_broccoli_model(const std::filesystem::path& path);

/// Per-stage mean milliseconds per frame as JSON {"cloud": 1.2, ...}.
nlohmann::json stages_json(const std::vector<StageTimer::Stage>& stages, long frames);

/// Table I + II metrics of an evaluation as JSON (NaN → null).
nlohmann::json eval_json(const pipeline::BroccoliEvalResult& r);

}  // namespace cropsight::cli
