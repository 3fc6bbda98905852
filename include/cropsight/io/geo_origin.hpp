#pragma once
// Where a sequence's field frame lies on the Earth: the optional file SEQ/geo_origin.yaml
//
//   latitude_deg: 52.1834        # WGS84 latitude of the field frame's origin, degrees north
//   longitude_deg: 0.1473        # WGS84 longitude of the origin, degrees east
//   altitude_m: 12.0             # height of the origin, metres (the GNSS source's datum; default 0)
//   field_x_azimuth_deg: 90      # compass azimuth of the field frame's +x axis: degrees clockwise
//                                # from true north (0 = x north, 90 = x east; default 90)
//
// The field frame (tracking/field_transform.hpp, poses.csv) is right-handed with z up, so +y is
// +x turned 90° anticlockwise seen from above: with x east (azimuth 90), y points north.
//
// Field ⇄ WGS84 goes through PROJ with a transverse Mercator projection centred on the origin
// (+proj=tmerc +lat_0 +lon_0 +k=1 +ellps=WGS84). Why that and not a tangent plane (PROJ's
// topocentric): a field is a few hundred metres, where both agree to well under a millimetre
// (tmerc's scale error at 1 km from its centre is 1e-8); tmerc is conformal, exact on the
// ellipsoid (PROJ's Poder/Engsager series) and two-dimensional, so heights pass through as
// altitude_m + z without a detour through geocentric coordinates. Grid north equals true north at
// the origin (the central meridian), so the azimuth is a plain rotation.
#include <Eigen/Core>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

namespace cropsight::io {

/// The contents of geo_origin.yaml (see the top of this file).
struct GeoOrigin {
  double latitude_deg = 0.0;
  double longitude_deg = 0.0;
  double altitude_m = 0.0;
  double field_x_azimuth_deg = 90.0;
  /// Throws Error(where, ...) when a value is out of range (latitude ±90, exclusive of the poles;
  /// longitude ±180; azimuth [0, 360); every value finite).
  void validate(const std::string& where) const;
};

/// A WGS84 position: degrees and metres.
struct Wgs84 {
  double latitude_deg = 0.0;
  double longitude_deg = 0.0;
  double altitude_m = 0.0;
};

inline constexpr const char* kGeoOriginFile = "geo_origin.yaml";

/// Reads a geo_origin.yaml. Throws Error(path, ...) on a missing file, bad YAML, an unknown or
/// missing key (latitude_deg and longitude_deg are required) or a value out of range.
GeoOrigin read_geo_origin(const std::filesystem::path& path);
/// SEQ/geo_origin.yaml when the sequence has one, else nullopt (same errors as read_geo_origin).
std::optional<GeoOrigin> read_sequence_geo_origin(const std::filesystem::path& sequence_dir);
/// The YAML text of `origin` (shortest text that reads back to the same values).
std::string geo_origin_yaml(const GeoOrigin& origin);
/// Writes geo_origin.yaml atomically.
void write_geo_origin(const std::filesystem::path& path, const GeoOrigin& origin);

/// Field frame ⇄ WGS84 for one origin, through PROJ. Holds its own PROJ context: use one object
/// per thread (PROJ objects are not thread-safe); no global state.
class GeoReference {
 public:
  /// Throws Error("geo origin", ...) when PROJ cannot build the projection.
  explicit GeoReference(const GeoOrigin& origin);
  ~GeoReference();
  GeoReference(GeoReference&&) noexcept;
  GeoReference& operator=(GeoReference&&) noexcept;

  /// A field-frame point (metres) as WGS84.
  Wgs84 to_wgs84(const Eigen::Vector3d& field) const;
  /// A WGS84 position as a field-frame point (metres).
  Eigen::Vector3d to_field(const Wgs84& position) const;
  const GeoOrigin& origin() const { return origin_; }

 private:
  struct Proj;
  GeoOrigin origin_;
  std::unique_ptr<Proj> proj_;
};

}  // namespace cropsight::io
