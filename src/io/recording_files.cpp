// The frame files of a recorder's folder, keyed and sorted by the last number of their name
// (recording_import.hpp lists the layouts).
#include <algorithm>
#include <cctype>
#include <map>

#include "cropsight/core/error.hpp"
#include "cropsight/io/file_names.hpp"
#include "cropsight/io/recording_import.hpp"

namespace cropsight::io {

namespace fs = std::filesystem;

namespace {

// The last number of a file stem: digits with an optional fractional part ("123", "1596.25").
// The stem of "frame-000123.depth.png" is "frame-000123.depth": its last number is 000123.
bool last_number(const std::string& stem, std::string& key) {
  int end = int(stem.size()) - 1;
  while (end >= 0 && !std::isdigit(static_cast<unsigned char>(stem[std::size_t(end)]))) --end;
  if (end < 0) return false;
  int begin = end;
  while (begin > 0 && std::isdigit(static_cast<unsigned char>(stem[std::size_t(begin - 1)]))) --begin;
  // A fraction "1596203844123.456": take the integer part before the dot too.
  if (begin >= 2 && stem[std::size_t(begin - 1)] == '.' &&
      std::isdigit(static_cast<unsigned char>(stem[std::size_t(begin - 2)]))) {
    int b2 = begin - 2;
    while (b2 > 0 && std::isdigit(static_cast<unsigned char>(stem[std::size_t(b2 - 1)]))) --b2;
    begin = b2;
  }
  key = stem.substr(std::size_t(begin), std::size_t(end - begin + 1));
  return true;
}

}  // namespace

std::vector<RecordingFile> list_recording(const fs::path& dir, const std::vector<std::string>& exts) {
  if (!fs::is_directory(dir)) throw Error(dir.string(), "not a directory");
  std::vector<RecordingFile> files;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (!e.is_regular_file() || std::find(exts.begin(), exts.end(), lower_extension(e.path())) == exts.end()) continue;
    RecordingFile f;
    f.path = e.path();
    if (!last_number(e.path().stem().string(), f.key))
      throw Error(f.path.string(), "file name has no frame number (accepted: docs/formats.md, Importing recordings)");
    f.value = std::stod(f.key);
    files.push_back(std::move(f));
  }
  std::string names;
  for (const auto& x : exts) names += (names.empty() ? "" : ", ") + x;
  if (files.empty()) throw Error(dir.string(), "no " + names + " files");
  std::sort(files.begin(), files.end(), [](const RecordingFile& a, const RecordingFile& b) {
    return a.value != b.value ? a.value < b.value : a.path < b.path;
  });
  for (std::size_t i = 1; i < files.size(); ++i)
    if (files[i].value == files[i - 1].value)
      throw Error(files[i].path.string(), "same frame number as " + files[i - 1].path.filename().string());
  return files;
}

}  // namespace cropsight::io
