// poses.csv and groundtruth.json: strict parsers (every problem names the file, and the line
// for CSV) and deterministic writers (fixed key order, shortest round-trip number format).
#include "sequence_text.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <set>
#include <sstream>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "json_file.hpp"
#include "number_text.hpp"

namespace cropsight::io::detail {

namespace fs = std::filesystem;

namespace {
constexpr const char* kPosesHeader = "frame,timestamp,x,y,z";
constexpr const char* kTimestampsHeader = "frame,timestamp";

std::vector<std::string_view> split(std::string_view line, char sep) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= line.size(); ++i) {
    if (i == line.size() || line[i] == sep) {
      out.push_back(line.substr(start, i - start));
      start = i + 1;
    }
  }
  return out;
}
}  // namespace

namespace {
// The rows of a per-frame CSV of the sequence format (poses.csv, timestamps.csv): the header
// exactly `header`, then one row per depth frame in order 0, 1, 2, ..., each a frame number and
// `values` finite numbers, the first of which is the timestamp.
std::vector<std::vector<double>> read_frame_rows(const fs::path& path, const std::string& header, int frames) {
  const std::string where = path.string();
  const std::string text = read_file(path);
  const std::size_t columns = split(header, ',').size();
  std::vector<std::vector<double>> rows;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  bool seen_header = false;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string_view l = trim(line);
    if (l.empty()) continue;
    if (!seen_header) {
      if (l != header) throw Error(where, "line " + std::to_string(line_no) + ": expected the header '" + header + "'");
      seen_header = true;
      continue;
    }
    const auto fields = split(l, ',');
    const std::string at = "line " + std::to_string(line_no) + ": ";
    if (fields.size() != columns)
      throw Error(where, at + "expected " + std::to_string(columns) + " comma-separated values, got " +
                             std::to_string(fields.size()));
    const auto frame = parse_int(fields[0]);
    if (!frame) throw Error(where, at + "frame must be an integer, got '" + std::string(fields[0]) + "'");
    if (*frame != long(rows.size()))
      throw Error(where, at + "expected frame " + std::to_string(rows.size()) + ", got " + std::to_string(*frame) +
                             " (rows must list frames 0, 1, 2, ... in order)");
    std::vector<double> v;
    for (std::size_t k = 1; k < fields.size(); ++k) {
      const auto d = parse_double(fields[k]);
      if (!d) throw Error(where, at + "expected a finite number, got '" + std::string(fields[k]) + "'");
      v.push_back(*d);
    }
    // Timestamps are seconds since the recording started; the temporal filter and the map assume
    // frames in time order.
    if (v[0] < 0.0) throw Error(where, at + "timestamp must be >= 0 (seconds), got " + std::string(fields[1]));
    if (!rows.empty() && v[0] < rows.back()[0])
      throw Error(where, at + "timestamp " + std::string(fields[1]) + " goes back in time (previous row " +
                             format_double(rows.back()[0]) + ")");
    rows.push_back(std::move(v));
  }
  if (!seen_header) throw Error(where, "empty file (expected the header '" + header + "')");
  if (int(rows.size()) != frames)
    throw Error(where, "has " + std::to_string(rows.size()) + " rows but the sequence has " + std::to_string(frames) +
                           " depth frames");
  return rows;
}
}  // namespace

std::vector<CameraPose> read_poses_csv(const fs::path& path, int frames) {
  std::vector<CameraPose> poses;
  for (const auto& v : read_frame_rows(path, kPosesHeader, frames))
    poses.push_back(CameraPose{int(poses.size()), v[0], {v[1], v[2], v[3]}});
  return poses;
}

std::string format_poses_csv(const std::vector<CameraPose>& poses) {
  std::string out = std::string(kPosesHeader) + "\n";
  for (const auto& p : poses) {
    out += std::to_string(p.frame) + "," + format_double(p.timestamp) + "," + format_double(p.position.x()) + "," +
           format_double(p.position.y()) + "," + format_double(p.position.z()) + "\n";
  }
  return out;
}

std::vector<double> read_timestamps_csv(const fs::path& path, int frames) {
  std::vector<double> out;
  for (const auto& v : read_frame_rows(path, kTimestampsHeader, frames)) out.push_back(v[0]);
  return out;
}

std::string format_timestamps_csv(const std::vector<double>& timestamps) {
  std::string out = std::string(kTimestampsHeader) + "\n";
  for (std::size_t i = 0; i < timestamps.size(); ++i)
    out += std::to_string(i) + "," + format_double(timestamps[i]) + "\n";
  return out;
}

GroundTruth read_groundtruth_json(const fs::path& path) {
  const std::string where = path.string();
  const nlohmann::json j = detail::read_json_file(path);
  if (!j.is_object()) throw Error(where, "expected a JSON object with \"instances\"");
  for (const auto& [key, value] : j.items())
    if (key != "instances" && key != "attributes") throw Error(where, "unknown key \"" + key + "\"");
  if (!j.contains("instances") || !j["instances"].is_array()) throw Error(where, "\"instances\" must be an array");
  GroundTruth truth;
  std::set<int> ids;
  int k = 0;
  for (const auto& inst : j["instances"]) {
    const std::string at = "instance " + std::to_string(k++) + ": ";
    if (!inst.is_object()) throw Error(where, at + "must be an object");
    InstanceTruth t;
    if (!inst.contains("id") || !inst["id"].is_number_integer()) throw Error(where, at + "\"id\" must be an integer");
    const long long id = inst["id"].get<long long>();
    if (id < 1 || id > 65535) throw Error(where, at + "\"id\" must be in 1..65535 (label image values)");
    t.id = int(id);
    if (!ids.insert(t.id).second) throw Error(where, at + "duplicate id " + std::to_string(id));
    if (!inst.contains("position") || !inst["position"].is_array() || inst["position"].size() != 3)
      throw Error(where, at + "\"position\" must be an array of 3 numbers (metres)");
    for (int c = 0; c < 3; ++c) {
      const auto& v = inst["position"][std::size_t(c)];
      if (!v.is_number()) throw Error(where, at + "\"position\" must be an array of 3 numbers (metres)");
      t.position[c] = v.get<double>();
    }
    if (!inst.contains("diameter_mm") || !inst["diameter_mm"].is_number() || inst["diameter_mm"].get<double>() < 0)
      throw Error(where, at + "\"diameter_mm\" must be a non-negative number");
    t.diameter_mm = inst["diameter_mm"].get<double>();
    for (const auto& [key, value] : inst.items()) {
      if (key == "id" || key == "position" || key == "diameter_mm") continue;
      if (value.is_boolean())
        t.extra[key] = value.get<bool>() ? 1.0 : 0.0;
      else if (value.is_number())
        t.extra[key] = value.get<double>();
      else
        throw Error(where, at + "\"" + key + "\" must be a number or boolean");
    }
    truth.instances.push_back(std::move(t));
  }
  if (j.contains("attributes")) {
    const auto& a = j["attributes"];
    if (!a.is_object()) throw Error(where, "\"attributes\" must be an object");
    for (const auto& [key, value] : a.items()) {
      if (value.is_string())
        truth.attributes[key] = value.get<std::string>();
      else if (value.is_primitive() && !value.is_null())
        truth.attributes[key] = value.dump();
      else
        throw Error(where, "attribute \"" + key + "\" must be a string, number or boolean");
    }
  }
  return truth;
}

std::string format_groundtruth_json(const GroundTruth& truth, const std::string& where) {
  // ordered_json keeps insertion order: id, position, diameter_mm, then extras sorted by name.
  nlohmann::ordered_json j;
  j["instances"] = nlohmann::ordered_json::array();
  std::set<int> ids;
  auto finite = [&](double v, const std::string& what) {
    if (!std::isfinite(v)) throw Error(where, "ground truth " + what + " is not finite");
    return v;
  };
  for (const auto& t : truth.instances) {
    if (t.id < 1 || t.id > 65535)
      throw Error(where, "ground-truth id " + std::to_string(t.id) + " is outside 1..65535");
    if (!ids.insert(t.id).second) throw Error(where, "duplicate ground-truth id " + std::to_string(t.id));
    nlohmann::ordered_json o;
    o["id"] = t.id;
    o["position"] = {finite(t.position.x(), "position"), finite(t.position.y(), "position"),
                     finite(t.position.z(), "position")};
    o["diameter_mm"] = finite(t.diameter_mm, "diameter_mm");
    for (const auto& [k, v] : t.extra) {
      if (k == "id" || k == "position" || k == "diameter_mm")
        throw Error(where, "extra truth key '" + k + "' is reserved");
      o[k] = finite(v, k);
    }
    j["instances"].push_back(std::move(o));
  }
  nlohmann::ordered_json attrs = nlohmann::ordered_json::object();
  for (const auto& [k, v] : truth.attributes) attrs[k] = v;
  j["attributes"] = std::move(attrs);
  return j.dump(2) + "\n";
}

}  // namespace cropsight::io::detail
