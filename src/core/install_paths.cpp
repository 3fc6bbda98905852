#include "cropsight/core/install_paths.hpp"

#include <cstdlib>

namespace cropsight {

namespace fs = std::filesystem;

fs::path executable_dir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : exe.parent_path();
}

fs::path data_dir() {
  if (const char* env = std::getenv("CROPSIGHT_DATA_DIR"); env && *env) return fs::path(env);
  const fs::path exe = executable_dir();
  if (exe.empty()) return {};
  const fs::path share = (exe / ".." / "share" / "cropsight").lexically_normal();
  std::error_code ec;
  return fs::is_directory(share, ec) ? share : fs::path();
}

}  // namespace cropsight
