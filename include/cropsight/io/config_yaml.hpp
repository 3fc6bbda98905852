#pragma once
// YAML presets (configs/*.yaml) as flat ConfigMaps: nested maps become dotted keys
// ("oes.depth_tolerance"), sequences become "[a, b, c]" text.
#include <filesystem>
#include <string>
#include <vector>

#include "cropsight/core/config.hpp"

namespace cropsight::io {

/// Throws Error(path, ...) for a missing file or malformed YAML (with line number).
ConfigMap load_config_map(const std::filesystem::path& path);
/// Resolves a preset name ("broccoli-uk") to configs/<name>.yaml in $CROPSIGHT_CONFIGS or the data
/// folder (core/install_paths.hpp), or returns `name_or_path` itself when it names an existing
/// file. Throws Error(name_or_path, ...) naming the folders looked in.
std::filesystem::path find_preset(const std::string& name_or_path);
/// Resolves a shipped model's name ("broccoli-oes-general", with or without its .json / .onnx /
/// .pt extension) to models/ of the data folder, the way find_preset resolves presets, or returns
/// `name_or_path` itself when it names an existing file. Throws Error(name_or_path, ...).
std::filesystem::path find_model(const std::string& name_or_path);
/// `path` as a preset file names it: a relative path is relative to the preset's folder, so that a
/// preset works from any working directory; empty and absolute paths come back unchanged.
std::string relative_to_preset(const std::filesystem::path& preset, const std::string& path);
/// The values of `preset` (find_preset; none when empty) overlaid with `sets` ("key=value", the
/// CLI's --set and the ROS nodes' ~set). Throws Error(file, ...) or Error("--set", ...).
ConfigMap load_preset_with_overrides(const std::string& preset, const std::vector<std::string>& sets);

}  // namespace cropsight::io
