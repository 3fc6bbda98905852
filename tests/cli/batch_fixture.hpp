#pragma once
// Shared by the batch CLI tests (local engine, tests/cli/test_batch_cli.cpp) and the Slurm tests
// (tests/cli/test_batch_slurm.cpp): four simulated passes over overlapping rows of one field
// (same seed; two start positions along the rows × two lateral offsets one row apart), each
// geo-referenced, and a manifest over them.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "testing/testing.hpp"

namespace cropsight::batch_test {

namespace fs = std::filesystem;
using cropsight::testing::run_cli;
using cropsight::testing::shell_quoted;

inline constexpr int kPassFrames = 16;

/// Simulates the four passes into `dir` (about 4 s each on the project's 2-core machine).
inline std::string simulate_passes(const fs::path& dir) {
  const char* sets[4] = {"--set motion.start_x_m=0 --set camera.lateral_offset_m=0",
                         "--set motion.start_x_m=0.4 --set camera.lateral_offset_m=0",
                         "--set motion.start_x_m=0 --set camera.lateral_offset_m=0.6",
                         "--set motion.start_x_m=0.4 --set camera.lateral_offset_m=0.6"};
  for (int i = 0; i < 4; ++i) {
    const auto r =
        run_cli("simulate broccoli --quiet --seed 7 --frames " + std::to_string(kPassFrames) + " " + sets[i] +
                " --geo-origin 52.2,0.12,90 --out " + shell_quoted(dir / ("pass" + std::to_string(i + 1))));
    if (r.exit_code != 0) return r.err;
  }
  return "";
}

inline fs::path write_manifest(const fs::path& file, const std::string& extra = "") {
  cropsight::testing::write_text(file,
                                 "recordings: [pass1, pass2, pass3, pass4]\npipeline:\n  crop: broccoli\n" + extra);
  return file;
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
