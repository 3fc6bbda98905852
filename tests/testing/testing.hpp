#pragma once
// Helpers shared by every module's tests.
#include <filesystem>
#include <functional>
#include <string>

namespace cropsight::testing {

/// A fresh directory under the system temp dir, removed (recursively) on destruction.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

/// Repository root (for fixtures under tests/fixtures, configs/, models/).
std::filesystem::path source_dir();
/// ../shared/data next to the repository, or $CROPSIGHT_DATA when set. May not exist.
std::filesystem::path shared_data_dir();
/// Path of the built CLI binary.
std::filesystem::path cli_path();

struct CommandResult {
  int exit_code = -1;
  std::string out;  ///< stdout
  std::string err;  ///< stderr
};
/// `p` in single quotes, for the shell command lines of run_cli (test paths hold no quote).
/// Writes `text` to `path` (a fixture file); throws std::runtime_error when it cannot.
void write_text(const std::filesystem::path& path, const std::string& text);

inline std::string shell_quoted(const std::filesystem::path& p) { return "'" + p.string() + "'"; }
/// Runs the CLI with `args` (a shell-quoted argument string) and captures its output.
CommandResult run_cli(const std::string& args);

/// The message of the cropsight::Error that `f()` throws ("where: problem"), or "" when it throws
/// none (another exception propagates).
std::string error_message(const std::function<void()>& f);

}  // namespace cropsight::testing

/// Skips the current test with a message when `path` does not exist.
#define CROPSIGHT_REQUIRE_DATA(path)                                                              \
  do {                                                                                            \
    if (!std::filesystem::exists(path))                                                           \
      GTEST_SKIP() << "shared data not found at " << (path) << " (see ../shared/data/README.md)"; \
  } while (0)
