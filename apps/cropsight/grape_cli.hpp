#pragma once
// What the grape sub-commands share: the JSON form of an evaluation (train grape, eval grape) and
// of a bunch (detect grape), and one RGB-D frame from its three files (roi-cloud, detect grape).
#include <nlohmann/json.hpp>
#include <string>

#include "cropsight/core/rgbd_frame.hpp"
#include "cropsight/pipeline/grape/eval.hpp"
#include "cropsight/pipeline/grape/frame_result.hpp"

namespace cropsight::cli {

/// {"clouds", "points", "oacc", "macc", "miou", "per_class": [{"label", "points", "accuracy",
/// "iou"}], "ms_per_cloud", "protocols": {"pooled_all_labels", "pooled_named_classes",
/// "per_cloud_named_classes", "per_cloud_all_labels": {"classes": [...], "miou"}}}; undefined
/// figures are null.
nlohmann::json grape_evaluation_json(const pipeline::grape::Figures& e);

/// One bunch of `detect grape` as cut_points.json lists it: {"file", "roi": [x, y, w, h], "points",
/// "label_counts", "cut_point": {"position_m", "direction", "confidence"} or null}.
nlohmann::json bunch_json(const pipeline::grape::Bunch& bunch, const std::string& file);

/// The frame of a colour image, a 16-bit depth image and its camera.yaml (intrinsics and
/// depth_scale). Throws Error naming the file: unreadable, depth not 16-bit, colour not 8-bit,
/// colour or camera size not the depth image's.
RgbdFrame read_grape_frame(const std::string& color, const std::string& depth, const std::string& camera);

}  // namespace cropsight::cli
