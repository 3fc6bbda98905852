#include "cropsight/core/config.hpp"

namespace cropsight {

std::pair<std::string, std::string> parse_assignment(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) throw Error("--set", "expected key=value, got '" + text + "'");
  auto trim = [](std::string s) {
    const auto b = s.find_first_not_of(" \t");
    const auto e = s.find_last_not_of(" \t");
    return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
  };
  return {trim(text.substr(0, eq)), trim(text.substr(eq + 1))};
}

}  // namespace cropsight
