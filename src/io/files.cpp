#include "cropsight/io/files.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>

#include "cropsight/core/error.hpp"

namespace cropsight::io {

namespace fs = std::filesystem;

namespace {
fs::path temp_sibling(const fs::path& path) {
  std::random_device rd;
  return path.parent_path() /
         ("." + path.filename().string() + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(rd() % 1000000));
}
}  // namespace

void write_atomic_with(const fs::path& path, const std::function<void(const fs::path& tmp)>& write) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw Error(path.string(), "is a directory (expected a file name to write)");
  if (!path.parent_path().empty()) {
    fs::create_directories(path.parent_path(), ec);
    if (ec) throw Error(path.string(), "cannot create directory: " + ec.message());
  }
  // Keep the extension last so that libraries choosing a format by extension still work.
  fs::path tmp = temp_sibling(path);
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
  const fs::path old = temp_sibling(dir).concat(".old");
  const bool had_old = fs::exists(dir, ec);
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

TempDirectory::TempDirectory(const fs::path& dir) : dir_(dir), path_(temp_sibling(dir)) {
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

void check_can_create(const fs::path& path) {
  fs::path at = fs::absolute(path).parent_path();
  std::error_code ec;
  while (!at.empty() && !fs::exists(at, ec) && at != at.parent_path()) at = at.parent_path();
  if (!fs::is_directory(at, ec)) throw Error(at.string(), "is not a folder: cannot create " + path.string() + " in it");
  if (::access(at.c_str(), W_OK | X_OK) != 0)
    throw Error(at.string(), std::string("cannot create ") + path.string() + " in it: " + std::strerror(errno));
}

std::string read_file(const fs::path& path) {
  // A directory opens as a stream on Linux and reads as empty: say what it is instead.
  if (std::error_code ec; fs::is_directory(path, ec)) throw Error(path.string(), "is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    if (!fs::exists(path)) throw Error(path.string(), "file not found");
    throw Error(path.string(), std::string("cannot read: ") + std::strerror(errno));
  }
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace cropsight::io
