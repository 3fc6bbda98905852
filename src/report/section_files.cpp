#include "section_files.hpp"

#include <sstream>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "io/json_file.hpp"

namespace cropsight::report::detail {

nlohmann::json read_json_file(const std::filesystem::path& path) {
  if (!std::filesystem::is_regular_file(path)) throw Error(path.string(), "no such file");
  return io::detail::read_json_file(path);
}

nlohmann::json read_json_object(const std::filesystem::path& path) {
  nlohmann::json j = read_json_file(path);
  if (!j.is_object()) throw Error(path.string(), "expected a JSON object");
  return j;
}

std::vector<nlohmann::json> read_json_lines(const std::filesystem::path& path) {
  if (!std::filesystem::is_regular_file(path)) throw Error(path.string(), "no such file");
  std::istringstream in(io::read_file(path));
  std::vector<nlohmann::json> out;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    out.push_back(io::detail::parse_json_text(line, path.string() + ": line " + std::to_string(n)));
    if (!out.back().is_object()) throw Error(path.string(), "line " + std::to_string(n) + ": expected a JSON object");
  }
  return out;
}

double number_at(const nlohmann::json& j, const std::string& pointer, const std::filesystem::path& path) {
  const nlohmann::json::json_pointer p(pointer);
  if (!j.contains(p) || !j.at(p).is_number()) throw Error(path.string(), "no number at " + pointer);
  return j.at(p).get<double>();
}

std::vector<std::string> section_commands(const std::filesystem::path& dir, std::vector<std::string> fallback) {
  const std::filesystem::path file = dir / "commands.txt";
  if (!std::filesystem::is_regular_file(file)) return fallback;
  std::istringstream in(io::read_file(file));
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);)
    if (line.find_first_not_of(" \t\r") != std::string::npos) lines.push_back(line);
  return lines;
}

std::filesystem::path required_file(const std::filesystem::path& path, const std::string& made_by) {
  if (!std::filesystem::is_regular_file(path)) throw Error(path.string(), "no such file (" + made_by + ")");
  return path;
}

}  // namespace cropsight::report::detail
