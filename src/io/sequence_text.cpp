// poses.csv and groundtruth.json: strict parsers (every problem names the file, and the line
// for CSV) and deterministic writers (fixed key order, shortest round-trip number format).
#include "sequence_text.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <set>
#include <sstream>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "number_text.hpp"

namespace cropsight::io::detail {

namespace fs = std::filesystem;

namespace {
constexpr const char* kPosesHeader = "frame,timestamp,x,y,z";

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

std::vector<CameraPose> read_poses_csv(const fs::path& path, int frames) {
  const std::string where = path.string();
  const std::string text = read_file(path);
  std::vector<CameraPose> poses;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  bool header = false;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string_view l = trim(line);
    if (l.empty()) continue;
    if (!header) {
      if (l != kPosesHeader)
        throw Error(where, "line " + std::to_string(line_no) + ": expected the header '" + kPosesHeader + "'");
      header = true;
      continue;
    }
    const auto fields = split(l, ',');
    const std::string at = "line " + std::to_string(line_no) + ": ";
    if (fields.size() != 5)
      throw Error(where, at + "expected 5 comma-separated values, got " + std::to_string(fields.size()));
    const auto frame = parse_int(fields[0]);
    if (!frame) throw Error(where, at + "frame must be an integer, got '" + std::string(fields[0]) + "'");
    if (*frame != long(poses.size()))
      throw Error(where, at + "expected frame " + std::to_string(poses.size()) + ", got " + std::to_string(*frame) +
                             " (rows must list frames 0, 1, 2, ... in order)");
    CameraPose p;
    p.frame = int(*frame);
    double v[4];
    for (int k = 0; k < 4; ++k) {
      const auto d = parse_double(fields[std::size_t(k) + 1]);
      if (!d)
        throw Error(where, at + "expected a finite number, got '" + std::string(fields[std::size_t(k) + 1]) + "'");
      v[k] = *d;
    }
    p.timestamp = v[0];
    p.position = {v[1], v[2], v[3]};
    // Timestamps are seconds since the recording started; the temporal filter and the map assume
    // frames in time order.
    if (p.timestamp < 0.0) throw Error(where, at + "timestamp must be >= 0 (seconds), got " + std::string(fields[1]));
    if (!poses.empty() && p.timestamp < poses.back().timestamp)
      throw Error(where, at + "timestamp " + std::string(fields[1]) + " goes back in time (previous row " +
                             format_double(poses.back().timestamp) + ")");
    poses.push_back(p);
  }
  if (!header) throw Error(where, "empty file (expected the header '" + std::string(kPosesHeader) + "')");
  if (int(poses.size()) != frames)
    throw Error(where, "has " + std::to_string(poses.size()) + " rows but the sequence has " + std::to_string(frames) +
                           " depth frames");
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

GroundTruth read_groundtruth_json(const fs::path& path) {
  const std::string where = path.string();
  const std::string text = read_file(path);
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {  // parse errors, and numbers out of range (1e999)
    throw Error(where, std::string("malformed JSON: ") + e.what());
  }
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
