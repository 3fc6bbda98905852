// GNSS fixes from CSV or NMEA, and their local field frame (io/gnss_poses.hpp).
#include "cropsight/io/gnss_poses.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <sstream>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "number_text.hpp"

namespace cropsight::io {

namespace fs = std::filesystem;

namespace {

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string field;
  std::istringstream in(s);
  while (std::getline(in, field, sep)) out.push_back(field);
  if (!s.empty() && s.back() == sep) out.emplace_back();
  return out;
}

std::vector<GnssFix> read_csv(const std::string& text, const std::string& where) {
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  const bool with_alt = line == "timestamp,lat,lon,alt";
  if (!with_alt && line != "timestamp,lat,lon")
    throw Error(where, "line 1: expected the header timestamp,lat,lon or timestamp,lat,lon,alt");
  std::vector<GnssFix> out;
  for (int n = 2; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (detail::trim(line).empty()) continue;
    const auto f = split(line, ',');
    std::vector<double> v;
    for (const auto& s : f)
      if (const auto d = detail::parse_double(s)) v.push_back(*d);
    if (f.size() != (with_alt ? 4u : 3u) || v.size() != f.size())
      throw Error(where, "line " + std::to_string(n) + ": expected " + (with_alt ? "4" : "3") + " numbers");
    GnssFix fix{v[0], {v[1], v[2], with_alt ? v[3] : 0.0}};
    if (std::abs(v[1]) >= 90 || std::abs(v[2]) > 180)
      throw Error(where, "line " + std::to_string(n) + ": latitude or longitude out of range");
    if (!out.empty() && fix.timestamp < out.back().timestamp)
      throw Error(where, "line " + std::to_string(n) + ": timestamp goes backwards");
    out.push_back(fix);
  }
  return out;
}

bool checksum_ok(const std::string& s) {
  const auto star = s.find('*');
  if (s.size() < 4 || s[0] != '$' || star == std::string::npos || star + 3 > s.size()) return false;
  unsigned sum = 0;
  for (std::size_t i = 1; i < star; ++i) sum ^= static_cast<unsigned char>(s[i]);
  unsigned given = 0;
  return std::sscanf(s.c_str() + star + 1, "%2x", &given) == 1 && given == sum;
}

// "5212.3456","N" → 52.20576; nullopt when empty or malformed.
std::optional<double> nmea_angle(const std::string& value, const std::string& hemisphere, int degree_digits) {
  const auto v = detail::parse_double(value);
  if (!v || value.size() < std::size_t(degree_digits)) return std::nullopt;
  const double deg = std::floor(*v / 100.0), minutes = *v - 100.0 * deg;
  const double a = deg + minutes / 60.0;
  if (hemisphere == "S" || hemisphere == "W") return -a;
  if (hemisphere == "N" || hemisphere == "E") return a;
  return std::nullopt;
}

std::optional<double> nmea_time(const std::string& hhmmss) {
  const auto v = detail::parse_double(hhmmss);
  if (!v || hhmmss.size() < 6) return std::nullopt;
  const int t = int(*v);
  return (t / 10000) * 3600.0 + (t / 100 % 100) * 60.0 + (*v - 100.0 * std::floor(*v / 100.0));
}

// Days since 1970-01-01 of an RMC date "ddmmyy" (years 2000-2099).
std::optional<long> nmea_days(const std::string& ddmmyy) {
  if (ddmmyy.size() != 6 || ddmmyy.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
  const int d = std::stoi(ddmmyy.substr(0, 2)), m = std::stoi(ddmmyy.substr(2, 2)),
            y = 2000 + std::stoi(ddmmyy.substr(4));
  // Howard Hinnant's days_from_civil.
  const int yy = y - (m <= 2), era = yy / 400, yoe = yy - era * 400;
  const int doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1, doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return long(era) * 146097 + doe - 719468;
}

// Long on purpose: one pass over the sentences, GGA and RMC side by side.
std::vector<GnssFix> read_nmea(const std::string& text, const std::string& where) {
  std::map<double, GnssFix> by_time;  // time of day → fix (GGA fills altitude, RMC may come first)
  std::optional<long> days;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.size() < 7 || !checksum_ok(line)) continue;
    const auto f = split(line.substr(0, line.find('*')), ',');
    // "$GPGGA" → "GGA"; a talker field too short to hold a type is no sentence we read.
    const std::string type = f[0].size() == 6 ? f[0].substr(3) : std::string();
    if (type == "GGA" && f.size() >= 10 && f[6] != "0" && !f[6].empty()) {
      const auto t = nmea_time(f[1]);
      const auto lat = nmea_angle(f[2], f[3], 4), lon = nmea_angle(f[4], f[5], 5);
      const auto alt = detail::parse_double(f[9]);
      if (!t || !lat || !lon) continue;
      by_time[*t] = {*t, {*lat, *lon, alt.value_or(0.0)}};
    } else if (type == "RMC" && f.size() >= 10 && f[2] == "A") {
      const auto t = nmea_time(f[1]);
      const auto lat = nmea_angle(f[3], f[4], 4), lon = nmea_angle(f[5], f[6], 5);
      if (!t || !lat || !lon) continue;
      if (!days) days = nmea_days(f[9]);
      by_time.emplace(*t, GnssFix{*t, {*lat, *lon, 0.0}});  // a GGA of the same time wins
    }
  }
  if (by_time.empty()) throw Error(where, "no GNSS fix (no valid GGA or RMC sentence)");
  std::vector<GnssFix> out;
  for (auto& [t, fix] : by_time) {
    if (days) fix.timestamp += 86400.0 * double(*days);
    out.push_back(fix);
  }
  return out;
}

}  // namespace

std::vector<GnssFix> read_gnss_fixes(const fs::path& path) {
  const std::string text = read_file(path);
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first != std::string::npos && text[first] == '$') return read_nmea(text, path.string());
  auto fixes = read_csv(text, path.string());
  if (fixes.empty()) throw Error(path.string(), "no GNSS fix (no rows after the header)");
  return fixes;
}

LocalTrack gnss_to_local(const std::vector<GnssFix>& fixes, std::optional<double> azimuth) {
  if (fixes.empty()) throw Error("gnss", "no GNSS fix");
  LocalTrack track;
  track.origin = {fixes.front().position.latitude_deg, fixes.front().position.longitude_deg,
                  fixes.front().position.altitude_m, 90.0};
  if (!azimuth) {
    // The direction of travel: east/north of the last fix in an x-east frame at the first one.
    const Eigen::Vector3d last = GeoReference(track.origin).to_field(fixes.back().position);
    if (std::hypot(last.x(), last.y()) < 1e-3)
      throw Error("gnss", "the first and last fixes coincide: give the field's x azimuth");
    double a = std::atan2(last.x(), last.y()) * 180.0 / M_PI;  // clockwise from north
    azimuth = a < 0 ? a + 360.0 : a;
  }
  track.origin.field_x_azimuth_deg = *azimuth >= 360.0 ? 0.0 : *azimuth;
  const GeoReference ref(track.origin);
  for (const GnssFix& f : fixes) {
    track.timestamps.push_back(f.timestamp);
    track.positions.push_back(ref.to_field(f.position));
  }
  return track;
}

}  // namespace cropsight::io
