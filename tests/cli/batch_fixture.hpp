#pragma once
// Shared by the batch CLI tests (local engine, tests/cli/test_batch_cli.cpp) and the Slurm tests
// (tests/cli/test_batch_slurm.cpp): four simulated passes over overlapping rows of one field
// (same seed; two start positions along the rows × two lateral offsets one row apart), each
// geo-referenced, and manifests over them.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "testing/testing.hpp"

namespace cropsight::batch_test {

namespace fs = std::filesystem;
using cropsight::testing::run_cli;
using cropsight::testing::shell_quoted;

inline constexpr int kPassFrames = 16;

/// The four passes, simulated once per build of the CLI and shared by every test process of it
/// (ctest runs each test in its own process; simulating them costs about 16 s): a folder under
/// the build tree named after the binary's time stamp and size. A pass folder appears whole (the
/// simulator renames it into place), so a process that finds it uses it, and one that loses a
/// race to simulate it finds it written by the other. Tests never modify these recordings.
/// Returns "" or the simulator's error.
inline std::string shared_passes(fs::path& dir) {
  const fs::path bin = cropsight::testing::cli_path();
  const auto stamp =
      std::to_string(fs::last_write_time(bin).time_since_epoch().count()) + "-" + std::to_string(fs::file_size(bin));
  dir = bin.parent_path().parent_path() / "test-fixtures" / ("batch-passes-" + stamp);
  fs::create_directories(dir);
  const char* sets[4] = {"--set motion.start_x_m=0 --set camera.lateral_offset_m=0",
                         "--set motion.start_x_m=0.4 --set camera.lateral_offset_m=0",
                         "--set motion.start_x_m=0 --set camera.lateral_offset_m=0.6",
                         "--set motion.start_x_m=0.4 --set camera.lateral_offset_m=0.6"};
  for (int i = 0; i < 4; ++i) {
    const fs::path pass = dir / ("pass" + std::to_string(i + 1));
    if (fs::exists(pass)) continue;
    const auto r = run_cli("simulate broccoli --quiet --seed 7 --frames " + std::to_string(kPassFrames) + " " +
                           sets[i] + " --geo-origin 52.2,0.12,90 --out " + shell_quoted(pass));
    if (r.exit_code != 0 && !fs::exists(pass)) return r.err;
  }
  return "";
}

/// A manifest over `passes` (absolute paths) with `extra` YAML appended.
inline fs::path write_manifest(const fs::path& file, const std::vector<fs::path>& passes,
                               const std::string& extra = "") {
  std::string list;
  for (const fs::path& p : passes) list += (list.empty() ? "" : ", ") + ("'" + p.string() + "'");
  cropsight::testing::write_text(file, "recordings: [" + list + "]\npipeline:\n  crop: broccoli\n" + extra);
  return file;
}
inline std::vector<fs::path> pass_paths(const fs::path& dir, int n = 4) {
  std::vector<fs::path> out;
  for (int i = 1; i <= n; ++i) out.push_back(dir / ("pass" + std::to_string(i)));
  return out;
}

inline std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Shard folders of a batch that hold their done marker, and those that do not.
inline int done_shards(const fs::path& batch) {
  int n = 0;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(batch / "shards", ec))
    if (e.path().filename().string()[0] != '.' && fs::exists(e.path() / "shard.json")) ++n;
  return n;
}
inline int incomplete_visible_shards(const fs::path& batch) {
  int n = 0;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(batch / "shards", ec))
    if (e.path().filename().string()[0] != '.' && !fs::exists(e.path() / "shard.json")) ++n;
  return n;
}

/// Starts the CLI in the background (its own process group); returns its pid.
inline pid_t start_cli(const std::string& args, const fs::path& log) {
  const pid_t pid = fork();
  if (pid == 0) {
    setpgid(0, 0);
    const std::string cmd =
        "exec '" + cropsight::testing::cli_path().string() + "' " + args + " >'" + log.string() + "' 2>&1 </dev/null";
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

/// Waits until `pred` holds (polling every 20 ms) or `seconds` pass; returns whether it held.
template <class Pred>
bool wait_for(Pred&& pred, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    if (pred()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return pred();
}

/// A number in a `batch --json` summary ("ran": 2 → 2); -1 when absent.
inline long json_number(const std::string& json, const std::string& key) {
  const auto at = json.find("\"" + key + "\":");
  if (at == std::string::npos) return -1;
  return std::stol(json.substr(at + key.size() + 3));
}

}  // namespace cropsight::batch_test
