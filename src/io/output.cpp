#include "cropsight/io/output.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

#include "cropsight/core/error.hpp"

namespace cropsight::io {

namespace fs = std::filesystem;

namespace {

// First line of a marker: what the file is, for a person who opens it.
constexpr const char* kMarkerHeader =
    "# cropsight output: written by the command below; --force replaces only these files";

bool is_within(const fs::path& inner, const fs::path& outer) {
  auto o = outer.begin(), i = inner.begin();
  for (; o != outer.end(); ++o, ++i)
    if (i == inner.end() || *i != *o) return false;
  return true;
}

// Every entry under `dir`, relative to it, sorted; the marker itself left out.
std::vector<std::string> entries_under(const fs::path& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    const std::string rel = it->path().lexically_relative(dir).string();
    if (rel != kOutputMarker) out.push_back(rel);
  }
  if (ec) throw Error(dir.string(), "cannot list the folder: " + ec.message());
  std::sort(out.begin(), out.end());
  return out;
}

// The nearest existing folder at or above `path` (absolute).
fs::path nearest_existing(const fs::path& path) {
  fs::path at = path;
  std::error_code ec;
  while (!fs::exists(at, ec) && at != at.parent_path()) at = at.parent_path();
  return at;
}

// Creates and removes a file in the nearest existing folder above `out`: the proof that the output
// can be created there (access() says yes to root on read-only or virtual file systems).
void probe_writable(const fs::path& out) {
  const fs::path at = nearest_existing(out.parent_path());
  std::error_code ec;
  if (!fs::is_directory(at, ec)) throw Error(out.string(), "cannot be created: " + at.string() + " is not a folder");
  const fs::path probe = temporary_sibling(at / ("." + out.filename().string() + "-probe"));
  errno = 0;
  std::ofstream f(probe, std::ios::binary);
  if (!f) {
    const std::string why = errno ? std::strerror(errno) : "cannot create a file there";
    throw Error(out.string(), "cannot be written (" + at.string() + ": " + why + ")");
  }
  f.close();
  fs::remove(probe, ec);
}

// The folder rules of output.hpp for an existing `dir` (resolved); errors name it as `name`, the
// user's spelling.
void check_existing_folder(const fs::path& dir, const std::string& name, const OutputPolicy& policy) {
  std::error_code ec;
  if (fs::is_empty(dir, ec) && !ec) return;
  const OutputMarker marker = read_output_marker(dir);
  if (!marker.present)
    throw Error(name, "is not empty and was not written by cropsight (it has no " + std::string(kOutputMarker) +
                          "); give a new or empty folder" +
                          (policy.force ? " (--force replaces only a cropsight output)" : ""));
  if (!policy.force)
    throw Error(name, "holds an earlier 'cropsight " + marker.command + "' output; --force replaces it");
  const std::set<std::string> listed(marker.entries.begin(), marker.entries.end());
  for (const std::string& e : entries_under(dir))
    if (!listed.count(e))
      throw Error(name, "holds '" + e +
                            "', which cropsight did not write; --force replaces only cropsight's own "
                            "files, so move it or give another folder");
}

// True when `dir` holds folders only (the chain this process created, nothing anyone put there).
bool only_folders_under(const fs::path& dir) {
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec))
    if (!it->is_directory() || it->is_symlink()) return false;
  return !ec;
}

}  // namespace

fs::path resolved_path(const fs::path& path) {
  std::error_code ec;
  fs::path p = fs::weakly_canonical(fs::absolute(path), ec);
  if (ec) p = fs::absolute(path).lexically_normal();
  if (p.filename().empty() && p.has_parent_path() && p != p.root_path()) p = p.parent_path();
  return p;
}

OutputMarker read_output_marker(const fs::path& dir) {
  OutputMarker m;
  std::error_code ec;
  if (!fs::is_regular_file(dir / kOutputMarker, ec)) return m;
  std::ifstream in(dir / kOutputMarker);
  std::string line;
  if (!std::getline(in, line) || line != kMarkerHeader) return m;
  if (!std::getline(in, line) || line.rfind("command: ", 0) != 0) return m;
  m.command = line.substr(9);
  while (std::getline(in, line))
    if (!line.empty()) m.entries.push_back(line);
  m.present = true;
  return m;
}

void check_not_an_input(const fs::path& out, const OutputPolicy& policy) {
  const fs::path o = resolved_path(out);
  for (const fs::path& input : policy.inputs) {
    if (input.empty()) continue;
    const fs::path in = resolved_path(input);
    if (o == in) throw Error(out.string(), "is an input of this command (" + input.string() + "); give another output");
    if (is_within(o, in))
      throw Error(out.string(), "lies inside the input " + input.string() + "; give an output outside the inputs");
    if (is_within(in, o))
      throw Error(out.string(), "contains the input " + input.string() + "; give an output outside the inputs");
  }
}

void check_output_file(const fs::path& file, const OutputPolicy& policy) {
  if (file.empty()) throw Error("--out", "empty output path");
  check_not_an_input(file, policy);
  const fs::path f = resolved_path(file);
  std::error_code ec;
  const auto st = fs::status(f, ec);
  if (fs::is_directory(st)) throw Error(file.string(), "is a folder; give the name of a file to write");
  if (fs::exists(st)) {
    if (!fs::is_regular_file(st)) throw Error(file.string(), "exists and is not a regular file");
    if (!policy.force) throw Error(file.string(), "exists; --force replaces it");
  }
  probe_writable(f);
}

namespace {
// The folder rules of output.hpp without the writability probe (OutputFolder proves that by
// creating its temporary).
void check_folder_rules(const fs::path& dir, const OutputPolicy& policy) {
  if (dir.empty()) throw Error("--out", "empty output path");
  check_not_an_input(dir, policy);
  const fs::path d = resolved_path(dir);
  if (d == d.root_path()) throw Error(dir.string(), "is the root folder; give a folder to write");
  std::error_code ec;
  const auto st = fs::status(d, ec);
  if (fs::exists(st)) {
    if (!fs::is_directory(st)) throw Error(dir.string(), "exists and is not a folder");
    check_existing_folder(d, dir.string(), policy);
  }
}
}  // namespace

void check_output_folder(const fs::path& dir, const OutputPolicy& policy) {
  check_folder_rules(dir, policy);
  probe_writable(resolved_path(dir));
}

OutputFolder::OutputFolder(const fs::path& dir, const OutputPolicy& policy)
    : dir_(resolved_path(dir)), policy_(policy) {
  check_folder_rules(dir, policy);
  const fs::path existing = nearest_existing(dir_.parent_path());
  if (existing != dir_.parent_path()) {
    // Remember the top folder created here, to remove it again when the run fails.
    created_parent_ = dir_.parent_path();
    while (created_parent_.parent_path() != existing) created_parent_ = created_parent_.parent_path();
  }
  std::error_code ec;
  fs::create_directories(dir_.parent_path(), ec);
  if (ec) throw Error(dir.string(), "cannot create the folder above it: " + ec.message());
  remove_stale_temporaries(dir_);
  tmp_ = temporary_sibling(dir_);
  fs::create_directory(tmp_, ec);
  if (ec) {
    if (!created_parent_.empty()) fs::remove_all(created_parent_, ec);
    throw Error(dir.string(), "cannot create a temporary folder beside it: " + ec.message());
  }
}

OutputFolder::~OutputFolder() {
  if (committed_) return;
  std::error_code ec;
  fs::remove_all(tmp_, ec);
  if (!created_parent_.empty() && only_folders_under(created_parent_)) fs::remove_all(created_parent_, ec);
}

void write_output_marker(const fs::path& dir, const std::string& command, const std::vector<std::string>& entries) {
  std::string text = std::string(kMarkerHeader) + "\ncommand: " + command + "\n";
  for (const std::string& e : entries) text += e + "\n";
  write_file_atomic(dir / kOutputMarker, text);
}

void OutputFolder::commit(const std::string& what) {
  if (committed_) return;
  std::error_code ec;
  // Another process may have created the folder meanwhile: the same rules decide.
  if (fs::exists(dir_, ec)) check_existing_folder(dir_, dir_.string(), policy_);
  std::string text = std::string(kMarkerHeader) + "\ncommand: " + policy_.command + "\n";
  for (const std::string& e : entries_under(tmp_)) text += e + "\n";
  write_file_atomic(tmp_ / kOutputMarker, text);
  replace_directory(tmp_, dir_, what);
  committed_ = true;
}

}  // namespace cropsight::io
