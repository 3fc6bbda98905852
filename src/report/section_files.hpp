#pragma once
// Reading the files the demo page's sections are made from (each command's --out or --json
// output, and the commands that wrote them): a missing file or a missing figure is one Error
// naming the file and what is missing, as every cropsight reader reports bad input.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace cropsight::report::detail {

/// The JSON document in `path`. Throws Error(path, ...) when it is missing or not JSON.
nlohmann::json read_json_file(const std::filesystem::path& path);
/// The JSON object in `path`. Throws Error(path, ...) when it is missing or not a JSON object.
nlohmann::json read_json_object(const std::filesystem::path& path);
/// One JSON object per non-empty line (harvest potato's messages). Throws Error(path, "line N: ...").
std::vector<nlohmann::json> read_json_lines(const std::filesystem::path& path);
/// The number at `pointer` ("/envelope/height_m") of `j`, read from `path`. Throws
/// Error(path, "no number at /envelope/height_m") when it is absent or not a number.
double number_at(const nlohmann::json& j, const std::string& pointer, const std::filesystem::path& path);
/// The non-empty lines of `dir`/commands.txt (the commands that made a section's files), or
/// `fallback` when the file is absent.
std::vector<std::string> section_commands(const std::filesystem::path& dir, std::vector<std::string> fallback);
/// `path` when it is a regular file; else Error(path, "no such file (" + made_by + ")").
std::filesystem::path required_file(const std::filesystem::path& path, const std::string& made_by);

}  // namespace cropsight::report::detail
