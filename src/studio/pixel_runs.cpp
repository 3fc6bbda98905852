// Pixel runs, the studio's mask wire format (pixel_runs.hpp).
#include "pixel_runs.hpp"

namespace cropsight::studio {

nlohmann::json to_runs(const std::vector<int>& ascending) {
  nlohmann::json runs = nlohmann::json::array();
  std::size_t k = 0;
  while (k < ascending.size()) {
    std::size_t end = k + 1;
    while (end < ascending.size() && ascending[end] == ascending[end - 1] + 1) ++end;
    runs.push_back(ascending[k]);
    runs.push_back(end - k);
    k = end;
  }
  return runs;
}

std::optional<std::vector<int>> from_runs(const nlohmann::json& runs, int pixels, std::string& error) {
  if (!runs.is_array() || runs.size() % 2 != 0) {
    error = "a mask must be an array of [start, length] pairs";
    return std::nullopt;
  }
  std::vector<int> out;
  for (std::size_t k = 0; k < runs.size(); k += 2) {
    const auto& a = runs[k];
    const auto& b = runs[k + 1];
    if (!a.is_number_integer() || !b.is_number_integer()) {
      error = "mask runs must be integers";
      return std::nullopt;
    }
    const long long start = a.get<long long>(), length = b.get<long long>();
    if (start < 0 || length < 1 || start + length > pixels || (long long)out.size() + length > pixels) {
      error = "mask run [" + std::to_string(start) + ", " + std::to_string(length) + "] leaves the frame";
      return std::nullopt;
    }
    for (long long p = start; p < start + length; ++p) out.push_back(int(p));
  }
  return out;
}

std::optional<std::vector<std::vector<int>>> parse_heads_body(const std::string& body, int pixels, std::string& error) {
  const nlohmann::json j = nlohmann::json::parse(body, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object() || !j.contains("heads") || !j["heads"].is_array()) {
    error = "expected {\"heads\": [runs, ...]}";
    return std::nullopt;
  }
  if (j["heads"].size() > std::size_t(pixels)) {
    error = "more heads than pixels";
    return std::nullopt;
  }
  // Overlapping heads are allowed (the later wins), but not without bound: a small body of long
  // runs could otherwise make the server hold gigabytes of pixel indices.
  std::vector<std::vector<int>> heads;
  std::size_t total = 0;
  for (const auto& runs : j["heads"]) {
    auto head = from_runs(runs, pixels, error);
    if (!head) return std::nullopt;
    total += head->size();
    if (total > 4 * std::size_t(pixels)) {
      error = "the masks cover the frame more than four times over";
      return std::nullopt;
    }
    heads.push_back(std::move(*head));
  }
  return heads;
}

}  // namespace cropsight::studio
