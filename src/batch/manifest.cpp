// The batch manifest (batch/manifest.hpp): YAML in, every check a batch needs before submission.
#include "cropsight/batch/manifest.hpp"

#include <yaml-cpp/yaml.h>

#include <map>
#include <set>

#include "cropsight/core/error.hpp"
#include "cropsight/io/config_yaml.hpp"
#include "cropsight/io/files.hpp"
#include "io/yaml_file.hpp"
#include "manifest_checks.hpp"

namespace cropsight::batch {

namespace fs = std::filesystem;

namespace {

struct ManifestYaml {
  YAML::Node root;
  std::string where;
  fs::path folder;

  // Every key of `node` must be one of `known` (a misspelt key would silently do nothing).
  void check_keys(const YAML::Node& node, const std::string& section, const std::set<std::string>& known) const {
    if (!node.IsMap()) throw Error(where, "'" + section + "' must be a mapping");
    for (const auto& kv : node) {
      const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : "?";
      if (!known.count(key)) throw Error(where, "unknown key '" + section + "." + key + "'");
    }
  }
  std::string text(const YAML::Node& node, const std::string& key) const {
    if (!node[key]) return "";
    if (!node[key].IsScalar()) throw Error(where, "'" + key + "' must be a single value");
    return node[key].Scalar();
  }
  int integer(const YAML::Node& node, const std::string& key, int fallback, int min) const {
    if (!node[key]) return fallback;
    int v = 0;
    try {
      v = node[key].as<int>();
    } catch (const YAML::Exception&) {
      throw Error(where, "'" + key + "' must be an integer");
    }
    if (v < min) throw Error(where, "'" + key + "' must be at least " + std::to_string(min));
    return v;
  }
  std::string file_or_name(const std::string& value) const { return detail::file_or_name(folder, value); }
};

void read_recordings(const ManifestYaml& y, Manifest& m) {
  const YAML::Node list = y.root["recordings"];
  if (!list || !list.IsSequence() || list.size() == 0)
    throw Error(y.where, "'recordings' must be a non-empty list of recording folders");
  for (const auto& item : list) {
    if (!item.IsScalar()) throw Error(y.where, "each recording must be a path");
    detail::add_recording(m, y.where, item.Scalar(), y.folder);
  }
  detail::check_distinct_names(m, y.where);
}

void read_pipeline(const ManifestYaml& y, Manifest& m) {
  const YAML::Node p = y.root["pipeline"];
  if (!p) throw Error(y.where, "missing 'pipeline' (crop, model, config, sets)");
  y.check_keys(p, "pipeline", {"crop", "model", "config", "sets", "detector"});
  detail::set_crop(m, y.where, y.text(p, "crop"));
  m.spec.model = y.file_or_name(y.text(p, "model"));
  m.spec.preset = y.file_or_name(y.text(p, "config"));
  m.spec.detector = y.file_or_name(y.text(p, "detector"));
  if (const YAML::Node sets = p["sets"]) {
    if (!sets.IsMap()) throw Error(y.where, "'pipeline.sets' must be a mapping of key: value");
    for (const auto& kv : sets) {
      if (!kv.first.IsScalar() || !kv.second.IsScalar())
        throw Error(y.where, "'pipeline.sets' entries must be key: value");
      m.spec.sets.push_back(kv.first.Scalar() + "=" + kv.second.Scalar());
    }
  }
}

void read_options(const ManifestYaml& y, Manifest& m) {
  if (const YAML::Node s = y.root["shards"]) {
    y.check_keys(s, "shards", {"frames_per_shard", "overlap_frames"});
    m.sharding.frames_per_shard = y.integer(s, "frames_per_shard", 0, 0);
    m.sharding.overlap_frames = y.integer(s, "overlap_frames", m.sharding.overlap_frames, 0);
  }
  if (const YAML::Node s = y.root["slurm"]) {
    y.check_keys(s, "slurm", {"partition", "account", "time", "mem", "cpus_per_task", "max_retries", "max_parallel"});
    SlurmOptions& o = m.slurm;
    if (s["partition"]) o.partition = y.text(s, "partition");
    if (s["account"]) o.account = y.text(s, "account");
    if (s["time"]) o.time = y.text(s, "time");
    if (s["mem"]) o.mem = y.text(s, "mem");
    o.cpus_per_task = y.integer(s, "cpus_per_task", o.cpus_per_task, 1);
    o.max_retries = y.integer(s, "max_retries", o.max_retries, 0);
    o.max_parallel = y.integer(s, "max_parallel", o.max_parallel, 0);
  }
}

}  // namespace

Manifest read_manifest(const fs::path& file) {
  if (file.extension() == ".csv") return read_manifest_csv(file);
  ManifestYaml y;
  y.where = file.string();
  y.folder = fs::absolute(file).parent_path();
  y.root = io::detail::load_yaml_file(file);
  if (!y.root.IsMap()) throw Error(y.where, "expected a YAML mapping with 'recordings' and 'pipeline'");
  y.check_keys(y.root, "manifest", {"recordings", "pipeline", "shards", "slurm"});
  Manifest m;
  m.file = fs::absolute(file);
  read_pipeline(y, m);  // first: the crop says what a recording is
  read_recordings(y, m);
  read_options(y, m);
  // The same call every shard makes: an unknown preset, model or key fails now, not on the cluster.
  detail::check_pipeline(m, y.where);
  return m;
}

}  // namespace cropsight::batch
