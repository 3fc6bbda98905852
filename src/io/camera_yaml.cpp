// camera.yaml of the sequence format: read with full validation, written deterministically.
#include <yaml-cpp/yaml.h>

#include <set>

#include "camera_info_yaml.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/sequence.hpp"
#include "number_text.hpp"
#include "yaml_file.hpp"
#include "yaml_key.hpp"

namespace cropsight::io {

namespace fs = std::filesystem;

namespace {

std::string scalar_text(const YAML::Node& node, const std::string& key, const std::string& where) {
  if (!node.IsScalar()) throw Error(where, "'" + key + "' must be a single value");
  return node.Scalar();
}

double get_double(const YAML::Node& root, const std::string& key, const std::string& where) {
  const YAML::Node n = root[key];
  if (!n) throw Error(where, "missing required key '" + key + "'");
  const std::string text = scalar_text(n, key, where);
  const auto v = detail::parse_double(text);
  if (!v) throw Error(where, "'" + key + "' must be a finite number, got '" + text + "'");
  return *v;
}

int get_int(const YAML::Node& root, const std::string& key, const std::string& where) {
  const YAML::Node n = root[key];
  if (!n) throw Error(where, "missing required key '" + key + "'");
  const std::string text = scalar_text(n, key, where);
  const auto v = detail::parse_int(text);
  if (!v || *v <= 0 || *v > 100000) throw Error(where, "'" + key + "' must be a positive integer, got '" + text + "'");
  return int(*v);
}

std::string quote(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out + "\"";
}

}  // namespace

CameraIntrinsics read_camera_yaml(const fs::path& path) {
  const std::string where = path.string();
  const YAML::Node root = detail::load_yaml_file(path);  // Error(path, "file not found") when absent
  if (root.IsMap())
    for (const auto& kv : root) detail::yaml_key(kv.first, where);  // a list or mapping as a key is an error
  const detail::CameraFileKind kind = detail::camera_file_kind(root);
  if (kind == detail::CameraFileKind::Unknown) throw Error(where, detail::accepted_camera_files());
  if (kind != detail::CameraFileKind::Cropsight) return detail::camera_from_ros_yaml(root, kind, where);
  static const std::set<std::string> known = {"width", "height",      "fx",         "fy",    "cx",
                                              "cy",    "depth_scale", "distortion", "sensor"};
  std::set<std::string> seen;
  for (const auto& kv : root) {
    const std::string key = detail::yaml_key(kv.first, where);
    if (!known.count(key)) throw Error(where, "unknown key '" + key + "'");
    // yaml-cpp keeps both entries and a lookup takes the first: a second fx would be ignored
    if (!seen.insert(key).second) throw Error(where, "duplicate key '" + key + "'");
  }
  CameraIntrinsics c;
  c.width = get_int(root, "width", where);
  c.height = get_int(root, "height", where);
  c.fx = get_double(root, "fx", where);
  c.fy = get_double(root, "fy", where);
  c.cx = get_double(root, "cx", where);
  c.cy = get_double(root, "cy", where);
  c.depth_scale = get_double(root, "depth_scale", where);
  if (const YAML::Node d = root["distortion"]) {
    if (!d.IsSequence()) throw Error(where, "'distortion' must be a list of numbers");
    for (std::size_t i = 0; i < d.size(); ++i) {
      const std::string t = scalar_text(d[i], "distortion", where);
      const auto v = detail::parse_double(t);
      if (!v) throw Error(where, "'distortion' must be a list of finite numbers, got '" + t + "'");
      c.distortion.push_back(*v);
    }
  }
  if (const YAML::Node s = root["sensor"]) c.sensor = scalar_text(s, "sensor", where);
  c.validate(where);
  return c;
}

void write_camera_yaml(const fs::path& path, const CameraIntrinsics& c) {
  c.validate(path.string());
  std::string y = "# cropsight sequence camera (docs/formats.md); depth_scale in metres per depth unit\n";
  y += "width: " + std::to_string(c.width) + "\n";
  y += "height: " + std::to_string(c.height) + "\n";
  y += "fx: " + detail::format_double(c.fx) + "\n";
  y += "fy: " + detail::format_double(c.fy) + "\n";
  y += "cx: " + detail::format_double(c.cx) + "\n";
  y += "cy: " + detail::format_double(c.cy) + "\n";
  y += "depth_scale: " + detail::format_double(c.depth_scale) + "\n";
  if (!c.distortion.empty()) {
    y += "distortion: [";
    for (std::size_t i = 0; i < c.distortion.size(); ++i) y += (i ? ", " : "") + detail::format_double(c.distortion[i]);
    y += "]\n";
  }
  if (!c.sensor.empty()) y += "sensor: " + quote(c.sensor) + "\n";
  write_file_atomic(path, y);
}

}  // namespace cropsight::io
