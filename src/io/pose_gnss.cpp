// GNSS positions as a pose file (io/gnss_poses.hpp: a `timestamp,lat,lon[,alt]` CSV or an NMEA
// log): the fixes in a local metric field frame, and the geo origin that ties that frame to WGS84
// travels with the track so that the imported sequence is geo-referenced (geo_origin.yaml).
#include "cropsight/io/gnss_poses.hpp"
#include "pose_text.hpp"

namespace cropsight::io::detail {

namespace fs = std::filesystem;

bool looks_like_pose_gnss(const fs::path&, std::string_view first_line) {
  if (!first_line.empty() && first_line.front() == '$') return true;  // NMEA 0183
  const auto header = pose_fields(first_line, ',');
  const auto has = [&](std::string_view name) {
    for (std::string_view h : header)
      if (h == name) return true;
    return false;
  };
  return has("lat") && has("lon");
}

PoseTrack read_pose_gnss(const fs::path& path, const std::string&) {
  const LocalTrack local = gnss_to_local(read_gnss_fixes(path));
  PoseTrack track;
  track.geo_origin = local.origin;
  for (std::size_t i = 0; i < local.positions.size(); ++i)
    add_pose(track, TimedPose{local.timestamps[i], local.positions[i], std::nullopt}, int(i) + 2, path);
  return track;
}

}  // namespace cropsight::io::detail
