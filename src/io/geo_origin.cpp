// geo_origin.yaml and the field ⇄ WGS84 conversion through PROJ (io/geo_origin.hpp).
#include "cropsight/io/geo_origin.hpp"

#include <proj.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <set>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "number_text.hpp"
#include "yaml_file.hpp"
#include "yaml_key.hpp"

namespace cropsight::io {

namespace fs = std::filesystem;

namespace {

constexpr double kDegToRad = M_PI / 180.0;

double geo_number(const YAML::Node& root, const std::string& key, const std::string& where,
                  std::optional<double> fallback) {
  const YAML::Node n = root[key];
  if (!n) {
    if (fallback) return *fallback;
    throw Error(where, "missing required key '" + key + "'");
  }
  if (!n.IsScalar()) throw Error(where, "'" + key + "' must be a single number");
  const auto v = detail::parse_double(n.Scalar());
  if (!v) throw Error(where, "'" + key + "' must be a finite number, got '" + n.Scalar() + "'");
  return *v;
}

}  // namespace

void GeoOrigin::validate(const std::string& where) const {
  if (!std::isfinite(latitude_deg) || std::abs(latitude_deg) >= 90.0)
    throw Error(where, "latitude_deg must lie strictly between -90 and 90");
  if (!std::isfinite(longitude_deg) || std::abs(longitude_deg) > 180.0)
    throw Error(where, "longitude_deg must lie in [-180, 180]");
  if (!std::isfinite(altitude_m)) throw Error(where, "altitude_m must be a finite number");
  if (!std::isfinite(field_x_azimuth_deg) || field_x_azimuth_deg < 0.0 || field_x_azimuth_deg >= 360.0)
    throw Error(where, "field_x_azimuth_deg must lie in [0, 360)");
}

GeoOrigin read_geo_origin(const fs::path& path) {
  const std::string where = path.string();
  const YAML::Node root = detail::load_yaml_file(path);
  if (!root.IsMap()) throw Error(where, "expected a YAML mapping with latitude_deg and longitude_deg");
  static const std::set<std::string> known = {"latitude_deg", "longitude_deg", "altitude_m", "field_x_azimuth_deg"};
  std::set<std::string> seen;
  for (const auto& kv : root) {
    const std::string key = detail::yaml_key(kv.first, where);
    if (!known.count(key)) throw Error(where, "unknown key '" + key + "'");
    if (!seen.insert(key).second) throw Error(where, "duplicate key '" + key + "'");
  }
  GeoOrigin g;
  g.latitude_deg = geo_number(root, "latitude_deg", where, std::nullopt);
  g.longitude_deg = geo_number(root, "longitude_deg", where, std::nullopt);
  g.altitude_m = geo_number(root, "altitude_m", where, 0.0);
  g.field_x_azimuth_deg = geo_number(root, "field_x_azimuth_deg", where, 90.0);
  g.validate(where);
  return g;
}

std::optional<GeoOrigin> read_sequence_geo_origin(const fs::path& sequence_dir) {
  const fs::path p = sequence_dir / kGeoOriginFile;
  if (!fs::exists(p)) return std::nullopt;
  return read_geo_origin(p);
}

std::string geo_origin_yaml(const GeoOrigin& g) {
  using detail::format_double;
  return "latitude_deg: " + format_double(g.latitude_deg) + "\nlongitude_deg: " + format_double(g.longitude_deg) +
         "\naltitude_m: " + format_double(g.altitude_m) +
         "\nfield_x_azimuth_deg: " + format_double(g.field_x_azimuth_deg) + "\n";
}

void write_geo_origin(const fs::path& path, const GeoOrigin& origin) {
  origin.validate(path.string());
  write_file_atomic(path, geo_origin_yaml(origin));
}

struct GeoReference::Proj {
  PJ_CONTEXT* ctx = nullptr;
  PJ* tmerc = nullptr;
  ~Proj() {
    if (tmerc) proj_destroy(tmerc);
    if (ctx) proj_context_destroy(ctx);
  }
};

GeoReference::GeoReference(const GeoOrigin& origin) : origin_(origin), proj_(std::make_unique<Proj>()) {
  origin.validate("geo origin");
  proj_->ctx = proj_context_create();
  // No network, no grids: a pure ellipsoidal projection needs neither, and nothing is fetched.
  proj_context_set_enable_network(proj_->ctx, 0);
  char def[256];
  std::snprintf(def, sizeof def, "+proj=tmerc +lat_0=%.17g +lon_0=%.17g +k=1 +x_0=0 +y_0=0 +ellps=WGS84",
                origin.latitude_deg, origin.longitude_deg);
  proj_->tmerc = proj_create(proj_->ctx, def);
  if (!proj_->tmerc)
    throw Error("geo origin", std::string("PROJ cannot build the projection: ") +
                                  proj_context_errno_string(proj_->ctx, proj_context_errno(proj_->ctx)));
}

GeoReference::~GeoReference() = default;
GeoReference::GeoReference(GeoReference&&) noexcept = default;
GeoReference& GeoReference::operator=(GeoReference&&) noexcept = default;

Wgs84 GeoReference::to_wgs84(const Eigen::Vector3d& field) const {
  // Field (x, y) → east/north: x has azimuth a (clockwise from north), y is x turned 90° anticlockwise.
  const double a = origin_.field_x_azimuth_deg * kDegToRad;
  const double east = field.x() * std::sin(a) - field.y() * std::cos(a);
  const double north = field.x() * std::cos(a) + field.y() * std::sin(a);
  const PJ_COORD lonlat = proj_trans(proj_->tmerc, PJ_INV, proj_coord(east, north, 0, 0));
  if (!std::isfinite(lonlat.lp.lam) || !std::isfinite(lonlat.lp.phi))
    throw Error("geo origin", "PROJ cannot convert a field point to WGS84");
  return {lonlat.lp.phi / kDegToRad, lonlat.lp.lam / kDegToRad, origin_.altitude_m + field.z()};
}

Eigen::Vector3d GeoReference::to_field(const Wgs84& p) const {
  const PJ_COORD en =
      proj_trans(proj_->tmerc, PJ_FWD, proj_coord(p.longitude_deg * kDegToRad, p.latitude_deg * kDegToRad, 0, 0));
  if (!std::isfinite(en.xy.x) || !std::isfinite(en.xy.y))
    throw Error("geo origin", "PROJ cannot convert a WGS84 position to the field frame");
  const double a = origin_.field_x_azimuth_deg * kDegToRad;
  // The inverse of the rotation in to_wgs84 (its transpose).
  const double x = en.xy.x * std::sin(a) + en.xy.y * std::cos(a);
  const double y = -en.xy.x * std::cos(a) + en.xy.y * std::sin(a);
  return {x, y, p.altitude_m - origin_.altitude_m};
}

}  // namespace cropsight::io
