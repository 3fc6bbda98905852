#pragma once
// Internal to the JSON readers (label files, ground truth, models, batch plans and records,
// report sections): a file's or a text's JSON, with every nlohmann exception of parsing — syntax
// errors and numbers out of range such as 1e999 alike — turned into the one-line error every
// reader gives.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"

namespace cropsight::io::detail {

/// The JSON of `text`, read from `where`. Throws Error(where, "malformed JSON: ...").
inline nlohmann::json parse_json_text(const std::string& text, const std::string& where) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw Error(where, std::string("malformed JSON: ") + e.what());
  }
}

/// The JSON of `path`. Throws Error(path, "file not found" / "malformed JSON: ...").
inline nlohmann::json read_json_file(const std::filesystem::path& path) {
  return parse_json_text(read_file(path), path.string());
}

}  // namespace cropsight::io::detail
