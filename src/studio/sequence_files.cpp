// The sequence files the studio may serve (studio/sequence_files.hpp).
#include "cropsight/studio/sequence_files.hpp"

#include <algorithm>
#include <system_error>

namespace cropsight::studio {

namespace fs = std::filesystem;

std::optional<fs::path> file_in_sequence(const fs::path& root, std::string_view relative) {
  if (relative.empty() || relative.front() == '/') return std::nullopt;
  if (relative.find('\\') != std::string_view::npos || relative.find('\0') != std::string_view::npos)
    return std::nullopt;
  // Segment by segment: no "..", ".", hidden names or empty segments ("a//b").
  std::size_t pos = 0;
  while (pos <= relative.size()) {
    std::size_t end = relative.find('/', pos);
    if (end == std::string_view::npos) end = relative.size();
    const std::string_view segment = relative.substr(pos, end - pos);
    if (segment.empty() || segment.front() == '.') return std::nullopt;
    pos = end + 1;
  }
  // Symbolic links: the resolved file must still lie under the resolved root.
  std::error_code ec;
  const fs::path base = fs::canonical(root, ec);
  if (ec) return std::nullopt;
  const fs::path file = fs::canonical(base / fs::path(std::string(relative)), ec);
  if (ec) return std::nullopt;
  const auto [stop, unused] = std::mismatch(base.begin(), base.end(), file.begin(), file.end());
  if (stop != base.end()) return std::nullopt;
  if (!fs::is_regular_file(file, ec)) return std::nullopt;
  return file;
}

}  // namespace cropsight::studio
