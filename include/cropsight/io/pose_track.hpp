#pragma once
// Camera poses recorded beside a recording (odometry, a motion-capture or SLAM trajectory), read
// for `cropsight import --poses FILE` and joined to the frames by time; the joined positions are
// the sequence's poses.csv (sequence.hpp).
//
// Formats, one reader function each, chosen by content (docs/formats.md, "Poses"):
//   csv  a header naming the columns timestamp (or time, t), x, y, z and optionally
//        qx, qy, qz, qw; other columns are ignored. Comma-separated.
//   tum  TUM RGB-D benchmark trajectories: `t x y z qx qy qz qw` per line, separated by spaces,
//        '#' comment lines.
//   gnss a `timestamp,lat,lon[,alt]` CSV or an NMEA log (io/gnss_poses.hpp): the fixes in a local
//        metric frame (origin at the first fix, x along the direction of travel), with the geo
//        origin that ties it to WGS84.
// Times are seconds on the clock of the recording's frames (file-name timestamps, bag stamps, or
// index / fps); positions metres in the field (odometry) frame; orientation the camera's, a unit
// quaternion (read and checked; poses.csv keeps positions only).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cropsight/io/geo_origin.hpp"

namespace cropsight::io {

struct TimedPose {
  double time = 0.0;                                   ///< seconds
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< metres
  std::optional<Eigen::Quaterniond> orientation;       ///< unit quaternion, when the file has one
};

struct PoseTrack {
  std::string format;                   ///< the reader's name ("csv", "tum", "gnss")
  std::vector<TimedPose> poses;         ///< strictly increasing time
  std::optional<GeoOrigin> geo_origin;  ///< gnss: where the positions' frame lies on the Earth
};

/// One pose file format. `accepts` looks at the file name and its first line that is neither
/// blank nor a comment; `read` parses the whole text, throwing Error(path, "line N: ...").
struct PoseFormat {
  const char* name;
  const char* description;  ///< for the error that lists the accepted formats
  bool (*accepts)(const std::filesystem::path& path, std::string_view first_line);
  PoseTrack (*read)(const std::filesystem::path& path, const std::string& text);
};

/// The accepted formats, tried in order; a new format is one reader and one entry here.
const std::vector<PoseFormat>& pose_formats();

/// Reads a pose file in the first format that accepts it. Throws Error(path, ...) for a file in
/// none of them (naming them), a non-finite number, a time that does not increase, or a
/// quaternion that is not of unit length (within 1e-3).
PoseTrack read_pose_track(const std::filesystem::path& path);

/// The position of the track at each of `frame_times` (seconds, the track's clock): linear
/// interpolation between the poses just before and just after, both within `tolerance_s` of the
/// frame; the nearer pose alone when only one is (the ends of the track). Throws
/// Error(where, ...) naming the first frame with no pose within the tolerance.
std::vector<Eigen::Vector3d> join_poses(const PoseTrack& track, const std::vector<double>& frame_times,
                                        double tolerance_s, const std::string& where);

}  // namespace cropsight::io
