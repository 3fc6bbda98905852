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
