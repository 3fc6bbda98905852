#pragma once
// Pixel sets as runs, the studio's wire format for masks: [start, length, start, length, ...]
// over row-major pixel indices. A head of 2000 pixels is about 40 runs (one per image row), so a
// frame's candidates are a few kilobytes of JSON instead of the indices themselves.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace cropsight::studio {

/// Runs of ascending pixel indices.
nlohmann::json to_runs(const std::vector<int>& ascending);

/// The pixel indices of `runs`, or nothing (with `error` set) when it is not an array of an even
/// number of integers, a run is empty or leaves [0, pixels), or the runs hold more than `pixels`
/// pixels in all (a body cannot make the server allocate more than one frame per head).
std::optional<std::vector<int>> from_runs(const nlohmann::json& runs, int pixels, std::string& error);

/// The heads of a label save's body, {"heads": [runs, ...]}, each as ascending-by-run pixel
/// indices; nothing (with `error` set) when the body is not that JSON or a mask is invalid
/// (from_runs), or the masks hold more than four frames' worth of pixels together.
std::optional<std::vector<std::vector<int>>> parse_heads_body(const std::string& body, int pixels, std::string& error);

}  // namespace cropsight::studio
