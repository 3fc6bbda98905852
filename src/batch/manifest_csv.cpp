// The batch manifest as CSV (batch/manifest.hpp): one row a recording, for scripts that list
// recordings with `find` or a spreadsheet.
#include <algorithm>
#include <map>
#include <sstream>

#include "cropsight/batch/manifest.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "manifest_checks.hpp"

namespace cropsight::batch {

namespace fs = std::filesystem;

namespace {

// The fields of one line; a field may be double-quoted (a path with a comma), "" inside quotes
// is one quote. Error(where, "line N: ...") for an unterminated quote.
std::vector<std::string> csv_fields(const std::string& line, const std::string& where, int line_no) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
      out.back() += '"', ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      out.emplace_back();
    } else {
      out.back() += c;
    }
  }
  if (quoted) throw Error(where, "line " + std::to_string(line_no) + ": unterminated quote");
  return out;
}

const char* const kColumns[] = {"recording",        "crop",          "model", "config", "detector", "sets",
                                "frames_per_shard", "overlap_frames"};

// The value every row gives a batch-wide column: empty cells inherit, two different values are an error.
struct BatchWideValues {
  std::string where;
  std::map<std::string, std::pair<std::string, int>> value;  // column → value, the line that gave it
  void add(const std::string& column, const std::string& v, int line) {
    if (v.empty()) return;
    const auto [it, fresh] = value.emplace(column, std::make_pair(v, line));
    if (!fresh && it->second.first != v)
      throw Error(where, "line " + std::to_string(line) + ": " + column + " '" + v + "' but line " +
                             std::to_string(it->second.second) + " says '" + it->second.first +
                             "' (one pipeline per batch)");
  }
  std::string get(const std::string& column) const {
    const auto it = value.find(column);
    return it == value.end() ? "" : it->second.first;
  }
  int integer(const std::string& column, int fallback) const {
    const std::string v = get(column);
    if (v.empty()) return fallback;
    if (v.find_first_not_of("0123456789") != std::string::npos || v.size() > 9)
      throw Error(where, column + " '" + v + "' is not a non-negative integer");
    return std::stoi(v);
  }
};

std::vector<std::string> split_sets(const std::string& sets) {
  std::vector<std::string> out;
  std::istringstream in(sets);
  for (std::string kv; in >> kv;) out.push_back(kv);
  return out;
}

}  // namespace

Manifest read_manifest_csv(const fs::path& file) {
  const std::string where = file.string(), text = io::read_file(file);
  const fs::path folder = fs::absolute(file).parent_path();
  std::istringstream in(text);
  std::vector<std::string> header;
  std::vector<std::pair<std::string, int>> recordings;  // as written, with their line
  BatchWideValues wide{where, {}};
  int line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    auto fields = csv_fields(line, where, line_no);
    if (header.empty()) {
      header = fields;
      for (const std::string& h : header)
        if (std::find(std::begin(kColumns), std::end(kColumns), h) == std::end(kColumns))
          throw Error(where,
                      "line " + std::to_string(line_no) + ": unknown column '" + h +
                          "' (recording, crop, model, config, detector, sets, frames_per_shard, overlap_frames)");
      if (std::find(header.begin(), header.end(), "recording") == header.end())
        throw Error(where, "line " + std::to_string(line_no) + ": the header needs a 'recording' column");
      continue;
    }
    if (fields.size() != header.size())
      throw Error(where, "line " + std::to_string(line_no) + ": " + std::to_string(fields.size()) +
                             " fields, the header has " + std::to_string(header.size()));
    for (std::size_t c = 0; c < header.size(); ++c) {
      if (header[c] == "recording")
        recordings.emplace_back(fields[c], line_no);
      else
        wide.add(header[c], fields[c], line_no);
    }
  }
  if (recordings.empty()) throw Error(where, "no recordings (a header line with 'recording', then one row each)");
  Manifest m;
  m.file = fs::absolute(file);
  detail::set_crop(m, where, wide.get("crop"));
  m.spec.model = detail::file_or_name(folder, wide.get("model"));
  m.spec.preset = detail::file_or_name(folder, wide.get("config"));
  m.spec.detector = detail::file_or_name(folder, wide.get("detector"));
  m.spec.sets = split_sets(wide.get("sets"));
  m.sharding.frames_per_shard = wide.integer("frames_per_shard", 0);
  m.sharding.overlap_frames = wide.integer("overlap_frames", m.sharding.overlap_frames);
  for (const auto& [rec, line] : recordings)
    detail::add_recording(m, where + ": line " + std::to_string(line), rec, folder);
  detail::check_distinct_names(m, where);
  detail::check_pipeline(m, where);
  return m;
}

}  // namespace cropsight::batch
