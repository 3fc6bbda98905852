// Checks shared by the manifest formats (manifest_checks.hpp).
#include "manifest_checks.hpp"

#include <map>

#include "cropsight/batch/crop_shards.hpp"
#include "cropsight/core/error.hpp"

namespace cropsight::batch::detail {

namespace fs = std::filesystem;

void set_crop(Manifest& m, const std::string& where, const std::string& crop) {
  if (crop.empty()) throw Error(where, "the crop is required (broccoli, potato, grape or seedling)");
  if (!batch_supports_crop(crop))
    throw Error(where, "crop '" + crop + "': batches run broccoli, potato, grape or seedling");
  m.crop = crop;
}

std::string file_or_name(const fs::path& folder, const std::string& value) {
  if (value.empty()) return value;
  const fs::path p = fs::path(value).is_absolute() ? fs::path(value) : folder / value;
  std::error_code ec;  // a name too long for a path is a shipped name to look up, not a crash
  return fs::is_regular_file(p, ec) ? p.lexically_normal().string() : value;
}

void add_recording(Manifest& m, const std::string& where, const std::string& text, const fs::path& folder) {
  if (text.empty()) throw Error(where, "a recording is an empty path");
  const fs::path rel = text;
  std::error_code ec;
  const fs::path path = fs::absolute(rel.is_absolute() ? rel : folder / rel, ec).lexically_normal();
  if (ec || !fs::is_directory(path, ec))
    throw Error(where,
                "recording " + text + " is not a folder" +
                    (path.extension() == ".bag" ? " (import a bag first: cropsight import --data BAG --out SEQ)" : ""));
  recording_frames(m.crop, path);  // opens it: Error(file, ...) names what is wrong inside it
  m.recordings.push_back(path);
}

void check_distinct_names(const Manifest& m, const std::string& where) {
  std::map<std::string, fs::path> by_name;  // shard folder name → recording
  for (const fs::path& r : m.recordings) {
    const auto [it, fresh] = by_name.emplace(r.filename().string(), r);
    if (!fresh)
      throw Error(where, "recordings " + it->second.string() + " and " + r.string() + " would both write shards/" +
                             it->first + " (give the folders distinct names)");
  }
}

void check_pipeline(const Manifest& m, const std::string& where) {
  try {
    check_crop_pipeline(m.crop, m.spec, m.recordings);
  } catch (const Error& e) {
    throw Error(where, "pipeline: " + std::string(e.what()));
  }
}

}  // namespace cropsight::batch::detail
