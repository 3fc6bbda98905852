#include "cropsight/io/files.hpp"

#include <fcntl.h>  // AT_FDCWD
#include <signal.h>
#include <stdio.h>  // renameat2, RENAME_EXCHANGE (glibc >= 2.28)
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <vector>

#include "cropsight/core/error.hpp"

namespace cropsight::io {

namespace fs = std::filesystem;

fs::path temporary_sibling(const fs::path& path) {
  std::random_device rd;
  return path.parent_path() /
         ("." + path.filename().string() + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(rd() % 1000000));
}

void remove_stale_temporaries(const fs::path& path) {
  const fs::path parent = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  const std::string prefix = "." + path.filename().string() + ".";
  std::error_code ec;
  std::vector<fs::path> stale;
  for (const auto& e : fs::directory_iterator(parent, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const std::string rest = name.substr(prefix.size());
    if (rest.rfind("tmp-", 0) != 0 && rest.rfind("old-", 0) != 0) continue;
    const std::size_t at = 4;  // after "tmp-" / "old-"
    const std::size_t dash = rest.find('-', at);
    if (dash == std::string::npos || dash == at) continue;
    const std::string pid_text = rest.substr(at, dash - at);
    if (!std::all_of(pid_text.begin(), pid_text.end(), [](char c) { return c >= '0' && c <= '9'; })) continue;
    const long pid = std::strtol(pid_text.c_str(), nullptr, 10);
    if (pid <= 0 || pid == long(::getpid())) continue;
    if (::kill(pid_t(pid), 0) == 0 || errno != ESRCH) continue;  // alive, or not ours to judge
    stale.push_back(e.path());
  }
  for (const auto& p : stale) fs::remove_all(p, ec);
}

void write_atomic_with(const fs::path& path, const std::function<void(const fs::path& tmp)>& write) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw Error(path.string(), "is a directory (expected a file name to write)");
  if (!path.parent_path().empty()) {
    fs::create_directories(path.parent_path(), ec);
    if (ec) throw Error(path.string(), "cannot create directory: " + ec.message());
  }
  // Keep the extension last so that libraries choosing a format by extension still work.
  fs::path tmp = temporary_sibling(path);
  tmp += path.extension();
  try {
    write(tmp);
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    const std::string why = ec.message();  // before remove() reuses ec
    fs::remove(tmp, ec);
    throw Error(path.string(), "cannot write: " + why);
  }
}

void write_file_atomic(const fs::path& path, const std::string& content) {
  write_atomic_with(path, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    if (!out) throw Error(path.string(), std::string("cannot open for writing: ") + std::strerror(errno));
    out.write(content.data(), std::streamsize(content.size()));
    out.flush();
    if (!out) throw Error(path.string(), "write failed (disk full?)");
  });
}

void replace_directory(const fs::path& tmp, const fs::path& dir, const std::string& what) {
  std::error_code ec;
  const bool had_old = fs::exists(dir, ec);
  if (had_old) {
    // One atomic swap: no moment without `dir`. EINVAL / ENOSYS: a file system (or kernel) that
    // cannot exchange; then the two renames below.
    if (::renameat2(AT_FDCWD, tmp.c_str(), AT_FDCWD, dir.c_str(), RENAME_EXCHANGE) == 0) {
      fs::remove_all(tmp, ec);  // the old contents
      return;
    }
    if (errno != EINVAL && errno != ENOSYS)
      throw Error(dir.string(), "cannot replace the previous " + what + ": " + std::strerror(errno));
  }
  const fs::path old = temporary_sibling(dir).concat(".old");
  if (had_old) {
    fs::rename(dir, old, ec);
    if (ec) throw Error(dir.string(), "cannot replace the previous " + what + ": " + ec.message());
  }
  fs::rename(tmp, dir, ec);
  if (ec) {
    const std::string why = ec.message();
    if (had_old) fs::rename(old, dir, ec);
    throw Error(dir.string(), "cannot write the " + what + ": " + why);
  }
  if (had_old) fs::remove_all(old, ec);
}

TempDirectory::TempDirectory(const fs::path& dir) : dir_(dir), path_(temporary_sibling(dir)) {
  remove_stale_temporaries(dir);
  std::error_code ec;
  fs::remove_all(path_, ec);
  fs::create_directories(path_, ec);
  if (ec) throw Error(dir.string(), "cannot create folder (a temporary beside it): " + ec.message());
}

TempDirectory::~TempDirectory() {
  std::error_code ec;
  if (!committed_) fs::remove_all(path_, ec);
}

void TempDirectory::commit(const std::string& what) {
  replace_directory(path_, dir_, what);
  committed_ = true;
}

std::string read_file(const fs::path& path) {
  // A directory opens as a stream on Linux and reads as empty: say what it is instead.
  if (std::error_code ec; fs::is_directory(path, ec)) throw Error(path.string(), "is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const int err = errno;
    // exists() without the error code would throw std::filesystem_error on a name the system
    // refuses (too long, a loop): the error names it instead (fuzzing finding 21).
    if (std::error_code ec; !fs::exists(path, ec) && !ec) throw Error(path.string(), "file not found");
    throw Error(path.string(), std::string("cannot read: ") + std::strerror(err));
  }
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace cropsight::io
