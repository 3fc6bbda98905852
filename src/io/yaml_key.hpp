#pragma once
// Internal to the YAML readers (camera.yaml, presets, stereo calibration): a mapping's key as
// text. yaml-cpp lets a key be a list or a mapping ("{{}}: 1", "[a]: 1"), and as<std::string>()
// on one throws YAML::TypedBadConversion, which no reader caught (found by fuzz_camera_yaml).
#include <yaml-cpp/yaml.h>

#include <string>

#include "cropsight/core/error.hpp"

namespace cropsight::io::detail {

/// The text of mapping key `key`; throws Error(where, ...) naming its line when it is not a
/// plain scalar.
inline std::string yaml_key(const YAML::Node& key, const std::string& where) {
  if (!key.IsScalar())
    throw Error(where, "line " + std::to_string(key.Mark().line + 1) + ": a key must be a plain name, not a " +
                           (key.IsSequence() ? "list"
                            : key.IsMap()    ? "mapping"
                                             : "null"));
  return key.Scalar();
}

}  // namespace cropsight::io::detail
