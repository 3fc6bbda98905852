#pragma once
// What the grape sub-commands (train grape, eval grape) share: the JSON form of an evaluation.
#include <nlohmann/json.hpp>

#include "cropsight/pipeline/grape/grape_eval.hpp"

namespace cropsight::cli {

/// {"clouds", "points", "oacc", "macc", "miou", "per_class": [{"label", "points", "accuracy",
/// "iou"}], "ms_per_cloud", "protocols": {"pooled_all_labels", "pooled_named_classes",
/// "per_cloud_named_classes", "per_cloud_all_labels": {"classes": [...], "miou"}}}; undefined
/// figures are null.
nlohmann::json grape_evaluation_json(const pipeline::GrapeEvaluation& e);

}  // namespace cropsight::cli
