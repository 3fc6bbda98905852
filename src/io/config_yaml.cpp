#include "cropsight/io/config_yaml.hpp"

#include <yaml-cpp/yaml.h>
#include <set>

#include <cstdlib>

#include "cropsight/core/error.hpp"
#include "cropsight/core/install_paths.hpp"
#include "cropsight/io/files.hpp"
#include "yaml_file.hpp"
#include "yaml_key.hpp"

namespace cropsight::io {

namespace fs = std::filesystem;

namespace {
void flatten(const YAML::Node& node, const std::string& prefix, ConfigMap& out, const fs::path& path) {
  switch (node.Type()) {
    case YAML::NodeType::Map: {
      std::set<std::string> seen;  // yaml-cpp keeps duplicate keys and lookups take the first: refuse them
      for (const auto& kv : node) {
        const std::string key = detail::yaml_key(kv.first, path.string());
        const std::string full = prefix.empty() ? key : prefix + "." + key;
        if (!seen.insert(key).second) throw Error(path.string(), "duplicate key '" + full + "'");
        flatten(kv.second, full, out, path);
      }
      break;
    }
    case YAML::NodeType::Sequence: {
      std::string text = "[";
      for (std::size_t i = 0; i < node.size(); ++i) {
        if (!node[i].IsScalar()) throw Error(path.string(), "'" + prefix + "' must be a list of scalars");
        text += (i ? ", " : "") + node[i].as<std::string>();
      }
      out[prefix] = text + "]";
      break;
    }
    case YAML::NodeType::Scalar:
      out[prefix] = node.as<std::string>();
      break;
    case YAML::NodeType::Null:
    case YAML::NodeType::Undefined:
      break;
  }
}
}  // namespace

namespace {
// The folders a name was looked up in, for the error line.
std::string looked_in(const std::vector<fs::path>& roots) {
  std::string out;
  for (const auto& r : roots) out += (out.empty() ? "" : ", ") + r.string();
  return out.empty() ? "no data folder: set CROPSIGHT_DATA_DIR" : out;
}
}  // namespace

ConfigMap load_config_map(const fs::path& path) {
  const YAML::Node root = detail::load_yaml_file(path);
  if (!root.IsMap() && !root.IsNull()) throw Error(path.string(), "expected a YAML mapping at the top level");
  ConfigMap out;
  flatten(root, "", out, path);
  return out;
}

std::string relative_to_preset(const fs::path& preset, const std::string& path) {
  if (path.empty() || fs::path(path).is_absolute()) return path;
  return (preset.parent_path() / path).lexically_normal().string();
}

fs::path find_preset(const std::string& name_or_path) {
  if (fs::exists(name_or_path)) return name_or_path;
  std::vector<fs::path> roots;
  if (const char* env = std::getenv("CROPSIGHT_CONFIGS")) roots.emplace_back(env);
  if (const fs::path data = data_dir(); !data.empty()) roots.push_back(data / "configs");
  for (const auto& r : roots) {
    const fs::path p = r / (name_or_path + ".yaml");
    if (fs::exists(p)) return p;
  }
  throw Error(name_or_path, "no such preset or file (looked in " + looked_in(roots) + ")");
}

fs::path find_model(const std::string& name_or_path) {
  if (fs::exists(name_or_path)) return name_or_path;
  std::vector<fs::path> roots;
  if (const fs::path data = data_dir(); !data.empty()) roots.push_back(data / "models");
  // A shipped model by its name, with or without its extension ("broccoli-oes-general").
  for (const auto& r : roots)
    for (const char* ext : {"", ".json", ".onnx", ".pt"}) {
      const fs::path p = r / (name_or_path + ext);
      if (fs::is_regular_file(p)) return p;
    }
  throw Error(name_or_path, "no such model file or shipped model (looked in " + looked_in(roots) + ")");
}

ConfigMap load_preset_with_overrides(const std::string& preset, const std::vector<std::string>& sets) {
  ConfigMap m;
  if (!preset.empty()) m = load_config_map(find_preset(preset));
  for (const auto& s : sets) {
    auto [k, v] = parse_assignment(s);
    m[k] = v;
  }
  return m;
}

}  // namespace cropsight::io
