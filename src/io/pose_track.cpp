// Pose files: the table of formats, the reader that picks one, and the join to frame times.
#include "cropsight/io/pose_track.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "number_text.hpp"
#include "pose_text.hpp"

namespace cropsight::io {

namespace fs = std::filesystem;

const std::vector<PoseFormat>& pose_formats() {
  static const std::vector<PoseFormat> formats = {
      {"csv", "CSV with a header naming timestamp, x, y, z [, qx, qy, qz, qw]", detail::looks_like_pose_csv,
       detail::read_pose_csv},
      {"tum", "TUM trajectory: 't x y z qx qy qz qw' per line", detail::looks_like_pose_tum, detail::read_pose_tum},
      {"gnss", "GNSS: CSV 'timestamp,lat,lon[,alt]' or an NMEA log (GGA, RMC)", detail::looks_like_pose_gnss,
       detail::read_pose_gnss},
  };
  return formats;
}

PoseTrack read_pose_track(const fs::path& path) {
  const std::string text = read_file(path);  // Error(path, ...) when missing or unreadable
  std::istringstream in(text);
  std::string line;
  std::string_view first;
  while (std::getline(in, line)) {
    first = detail::trim(line);
    if (!first.empty() && first.front() != '#') break;
    first = {};
  }
  if (first.empty()) throw Error(path.string(), "no poses (the file is empty or only comments)");
  std::string accepted;
  for (const PoseFormat& f : pose_formats()) {
    if (f.accepts(path, first)) {
      PoseTrack track = f.read(path, text);
      if (track.poses.empty()) throw Error(path.string(), "no poses after the header");
      track.format = f.name;
      return track;
    }
    accepted += std::string(accepted.empty() ? "" : "; ") + f.name + ": " + f.description;
  }
  throw Error(path.string(), "not a pose file in a known format (" + accepted + ")");
}

std::vector<Eigen::Vector3d> join_poses(const PoseTrack& track, const std::vector<double>& frame_times,
                                        double tolerance_s, const std::string& where) {
  const auto& p = track.poses;
  std::vector<Eigen::Vector3d> out;
  out.reserve(frame_times.size());
  for (std::size_t i = 0; i < frame_times.size(); ++i) {
    const double t = frame_times[i];
    // The first pose later than t, and the one before it.
    const auto after = std::upper_bound(p.begin(), p.end(), t, [](double v, const TimedPose& q) { return v < q.time; });
    const bool has_after = after != p.end() && after->time - t <= tolerance_s;
    const bool has_before = after != p.begin() && t - std::prev(after)->time <= tolerance_s;
    if (has_before && has_after) {
      const TimedPose& a = *std::prev(after);
      const double w = (t - a.time) / (after->time - a.time);
      out.push_back((1.0 - w) * a.position + w * after->position);
    } else if (has_before || has_after) {
      out.push_back(has_before ? std::prev(after)->position : after->position);
    } else {
      throw Error(where, "no pose within " + detail::format_double(tolerance_s) + " s of frame " + std::to_string(i) +
                             " at t = " + detail::format_double(t) + " s (the poses cover " +
                             detail::format_double(p.front().time) + " .. " + detail::format_double(p.back().time) +
                             " s)");
    }
  }
  return out;
}

namespace detail {

std::vector<std::string_view> pose_fields(std::string_view line, char sep) {
  std::vector<std::string_view> out;
  if (sep != ' ') {
    std::size_t start = 0;
    for (std::size_t i = 0; i <= line.size(); ++i)
      if (i == line.size() || line[i] == sep) {
        out.push_back(trim(line.substr(start, i - start)));
        start = i + 1;
      }
    return out;
  }
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

double pose_number(std::string_view text, const char* column, int line, const fs::path& path) {
  const auto v = parse_double(text);
  if (!v)
    throw Error(path.string(), "line " + std::to_string(line) + ": " + column + " must be a finite number, got '" +
                                   std::string(text) + "'");
  return *v;
}

void add_pose(PoseTrack& track, TimedPose pose, int line, const fs::path& path) {
  const std::string at = "line " + std::to_string(line) + ": ";
  // Frames are joined by time: a track that goes back (a clock reset, two logs concatenated) has
  // no single pose at a time, and a NaN time never compares.
  if (!track.poses.empty() && !(pose.time > track.poses.back().time))
    throw Error(path.string(), at + "time " + format_double(pose.time) + " s does not increase (previous " +
                                   format_double(track.poses.back().time) + " s)");
  if (pose.orientation && std::abs(pose.orientation->norm() - 1.0) > 1e-3)
    throw Error(path.string(), at + "quaternion qx qy qz qw is not of unit length (norm " +
                                   format_double(pose.orientation->norm()) + ")");
  track.poses.push_back(pose);
}

}  // namespace detail

}  // namespace cropsight::io
