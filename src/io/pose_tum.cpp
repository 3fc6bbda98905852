// TUM RGB-D benchmark trajectories (the format of evo, ORB-SLAM and most SLAM tools' output):
// `timestamp tx ty tz qx qy qz qw` per line, '#' comments.
#include <sstream>

#include "cropsight/core/error.hpp"
#include "number_text.hpp"
#include "pose_text.hpp"

namespace cropsight::io::detail {

namespace fs = std::filesystem;

bool looks_like_pose_tum(const fs::path&, std::string_view first_line) {
  const auto f = pose_fields(first_line, ' ');
  if (f.size() != 8) return false;
  for (std::string_view v : f)
    if (!parse_double(v) && v != "nan" && v != "NaN") return false;  // NaN: the reader names the line
  return true;
}

PoseTrack read_pose_tum(const fs::path& path, const std::string& text) {
  static const char* const kColumns[8] = {"t", "x", "y", "z", "qx", "qy", "qz", "qw"};
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  PoseTrack track;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string_view l = trim(line);
    if (l.empty() || l.front() == '#') continue;
    const auto f = pose_fields(l, ' ');
    if (f.size() != 8)
      throw Error(path.string(), "line " + std::to_string(line_no) + ": expected 8 values 't x y z qx qy qz qw', got " +
                                     std::to_string(f.size()));
    double v[8];
    for (int k = 0; k < 8; ++k) v[k] = pose_number(f[std::size_t(k)], kColumns[k], line_no, path);
    add_pose(track, TimedPose{v[0], {v[1], v[2], v[3]}, Eigen::Quaterniond(v[7], v[4], v[5], v[6])}, line_no, path);
  }
  return track;
}

}  // namespace cropsight::io::detail
