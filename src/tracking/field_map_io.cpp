#include "cropsight/tracking/field_map_io.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"

namespace cropsight::tracking {

namespace {
const char* kHeader =
    "id,x_m,y_m,z_m,diameter_mm,bbox_diameter_mm,hull_diameter_mm,frames_seen,first_frame,last_frame,score,"
    "harvestable";
}

std::string field_map_csv(const std::vector<TrackedHead>& heads) {
  std::string out = std::string(kHeader) + "\n";
  char buf[512];
  for (const auto& h : heads) {
    std::snprintf(buf, sizeof buf, "%d,%.4f,%.4f,%.4f,%.1f,%.1f,%.1f,%d,%d,%d,%.3f,%d\n", h.id, h.position.x(),
                  h.position.y(), h.position.z(), h.diameter_mm, h.bbox_mm, h.hull_mm, h.frames_seen, h.first_frame,
                  h.last_frame, h.score, h.harvestable ? 1 : 0);
    out += buf;
  }
  return out;
}

void write_field_map(const std::filesystem::path& path, const std::vector<TrackedHead>& heads) {
  io::write_file_atomic(path, field_map_csv(heads));
}

std::vector<TrackedHead> read_field_map(const std::filesystem::path& path) {
  const std::string text = io::read_file(path);
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line) || line != kHeader)
    throw Error(path.string(), "not a field map (expected the header '" + std::string(kHeader) + "')");
  std::vector<TrackedHead> heads;
  int n = 1;
  while (std::getline(in, line)) {
    ++n;
    if (line.empty()) continue;
    const std::string where = path.string() + " line " + std::to_string(n);
    std::vector<std::string> f;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) f.push_back(cell);
    if (f.size() != 12) throw Error(where, "expected 12 comma-separated fields, got " + std::to_string(f.size()));
    try {
      std::size_t used = 0;
      auto num = [&](const std::string& s) {
        const double v = std::stod(s, &used);
        if (used != s.size() || !std::isfinite(v)) throw std::invalid_argument(s);
        return v;
      };
      auto integer = [&](const std::string& s) {
        const int v = std::stoi(s, &used);
        if (used != s.size()) throw std::invalid_argument(s);
        return v;
      };
      TrackedHead h;
      h.id = integer(f[0]);
      h.position = {num(f[1]), num(f[2]), num(f[3])};
      h.diameter_mm = num(f[4]);
      h.bbox_mm = num(f[5]);
      h.hull_mm = num(f[6]);
      h.frames_seen = integer(f[7]);
      h.first_frame = integer(f[8]);
      h.last_frame = integer(f[9]);
      h.score = num(f[10]);
      const int harvest = integer(f[11]);
      if (harvest != 0 && harvest != 1) throw std::invalid_argument(f[11]);
      h.harvestable = harvest == 1;
      heads.push_back(h);
    } catch (const std::logic_error&) {
      throw Error(where, "malformed number in '" + line + "'");
    }
  }
  return heads;
}

}  // namespace cropsight::tracking
