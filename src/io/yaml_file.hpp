#pragma once
// Internal to the YAML readers (camera.yaml, presets, extrinsics, geo_origin.yaml, batch
// manifests): a file's YAML, with yaml-cpp's parse error turned into the one-line error every
// reader gives.
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <string>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"

namespace cropsight::io::detail {

/// The YAML of `path`. Throws Error(path, "file not found" / "malformed YAML at line N: ...").
inline YAML::Node load_yaml_file(const std::filesystem::path& path) {
  const std::string text = read_file(path);
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw Error(path.string(), "malformed YAML at line " + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
}

}  // namespace cropsight::io::detail
