#pragma once
// GNSS positions of a recording as camera positions in a local metric field frame plus the
// geo_origin.yaml that ties that frame to WGS84 (io/geo_origin.hpp), for `--poses` of users'
// recordings. Two inputs:
//
// - CSV with the header `timestamp,lat,lon` or `timestamp,lat,lon,alt`: seconds (any epoch,
//   never decreasing), WGS84 degrees, metres. Every row must parse; errors name file and line.
// - NMEA 0183 (.nmea, .txt, .log): GGA and RMC sentences from any talker ($GP, $GN, $GL, ...).
//   Sentences whose checksum does not match, and GGA with fix quality 0 or RMC with status V, are
//   skipped (a serial log has the odd garbled line); other sentences are ignored. Time: the UTC
//   time of day, plus RMC's date when the log has one (seconds since 1970-01-01, else since the
//   day's midnight). A GGA and an RMC of the same time are one fix (GGA's altitude: metres above
//   mean sea level, as the receiver reports it). No fix at all is an error naming the file.
//
// The local frame (gnss_to_local): origin at the first fix, z up, x along `field_x_azimuth_deg`
// — by default the direction from the first fix to the last, i.e. along the row for a pass that
// drives one row, which is the simulator's and the temporal filter's convention (field x along
// the row, tracking/field_transform.hpp). Positions are the GNSS antenna's: a lever arm to the
// camera is not applied.
#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <vector>

#include "cropsight/io/geo_origin.hpp"

namespace cropsight::io {

struct GnssFix {
  double timestamp = 0.0;  ///< seconds (see the top of this file)
  Wgs84 position;
};

/// Reads a CSV or NMEA file as above (NMEA when the first non-blank character is '$').
std::vector<GnssFix> read_gnss_fixes(const std::filesystem::path& path);

struct LocalTrack {
  GeoOrigin origin;                        ///< what geo_origin.yaml holds
  std::vector<double> timestamps;          ///< seconds, as read
  std::vector<Eigen::Vector3d> positions;  ///< field frame, metres
};

/// The fixes in a local frame (see the top of this file). `field_x_azimuth_deg` overrides the
/// direction of x. Throws Error("gnss", ...) when there is no fix or, without an override, the
/// first and last fixes coincide (no direction of travel).
LocalTrack gnss_to_local(const std::vector<GnssFix>& fixes, std::optional<double> field_x_azimuth_deg = std::nullopt);

}  // namespace cropsight::io
