// Pose CSV: columns found by the header's names, so that a logger's extra columns (speed,
// covariance) and any column order are accepted.
#include <array>
#include <optional>
#include <sstream>

#include "cropsight/core/error.hpp"
#include "number_text.hpp"
#include "pose_text.hpp"

namespace cropsight::io::detail {

namespace fs = std::filesystem;

namespace {
std::optional<std::size_t> column_of(const std::vector<std::string_view>& header,
                                     std::initializer_list<std::string_view> names) {
  for (std::size_t i = 0; i < header.size(); ++i)
    for (std::string_view n : names)
      if (header[i] == n) return i;
  return std::nullopt;
}
}  // namespace

bool looks_like_pose_csv(const fs::path&, std::string_view first_line) {
  const auto header = pose_fields(first_line, ',');
  return header.size() >= 4 && column_of(header, {"timestamp", "time", "t"}) && column_of(header, {"x"});
}

PoseTrack read_pose_csv(const fs::path& path, const std::string& text) {
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  std::vector<std::string_view> header;
  std::string header_text;
  std::array<std::optional<std::size_t>, 8> col;  // t x y z qx qy qz qw
  static const char* const kNames[8] = {"timestamp", "x", "y", "z", "qx", "qy", "qz", "qw"};
  PoseTrack track;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string_view l = trim(line);
    if (l.empty() || l.front() == '#') continue;
    if (header.empty()) {
      header_text = l;
      header = pose_fields(header_text, ',');
      col[0] = column_of(header, {"timestamp", "time", "t"});
      for (int k = 1; k < 8; ++k) col[std::size_t(k)] = column_of(header, {kNames[k]});
      for (int k = 0; k < 4; ++k)
        if (!col[std::size_t(k)])
          throw Error(path.string(), "line " + std::to_string(line_no) + ": the header has no column '" + kNames[k] +
                                         "' (needs timestamp, x, y, z)");
      continue;
    }
    const auto f = pose_fields(l, ',');
    if (f.size() != header.size())
      throw Error(path.string(), "line " + std::to_string(line_no) + ": expected " + std::to_string(header.size()) +
                                     " values as in the header, got " + std::to_string(f.size()));
    double v[8] = {0, 0, 0, 0, 0, 0, 0, 1};
    for (int k = 0; k < 8; ++k)
      if (col[std::size_t(k)]) v[k] = pose_number(f[*col[std::size_t(k)]], kNames[k], line_no, path);
    TimedPose p{v[0], {v[1], v[2], v[3]}, std::nullopt};
    if (col[4] || col[5] || col[6] || col[7]) p.orientation = Eigen::Quaterniond(v[7], v[4], v[5], v[6]);
    add_pose(track, p, line_no, path);
  }
  return track;
}

}  // namespace cropsight::io::detail
