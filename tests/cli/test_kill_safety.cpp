// Kill safety (item 4): the commands that write outputs are killed with SIGKILL at seeded
// random moments spread over their run time (measured first on a clean run) and must leave
// nothing partial under a final name: each output is either absent or byte-identical to the clean
// run's, and anything else beside them is a temporary (".NAME.tmp-*"). Then the same
// command, run again in the same folder over whatever the kill left, must succeed and write the
// clean run's outputs. Half of the kills hit a run that replaces an earlier complete output (the
// clean one, copied in first), so the replacement path is killed too: there the earlier output
// must stay visible until the new one replaces it. Folder outputs' reruns must also remove what the
// killed run left beside them.
//
// Its own executable and one ctest, KillSafety (labels cli, kill; top-level CMakeLists.txt): it
// starts the CLI about 60 times, so one process builds the inputs once for every command, and a
// run can select or skip it by label.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "testing/testing.hpp"

namespace fs = std::filesystem;
using cropsight::testing::TempDir;
using Clock = std::chrono::steady_clock;

namespace {

// One command under test: its arguments (relative output names: it runs in its own folder, so
// every run's command line, and therefore every output that records it, is the same) and the
// names of the files or folders it writes.
struct Case {
  std::string name;
  std::vector<std::string> args;
  std::vector<std::string> outputs;
  int kills = 4;
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A file's or folder's whole content (relative path -> bytes; folders as "<dir>" entries), or
// nullopt when `p` does not exist.
using Snapshot = std::map<std::string, std::string>;
std::optional<Snapshot> snapshot(const fs::path& p) {
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(p, ec))) return std::nullopt;
  Snapshot s;
  if (!fs::is_directory(p)) {
    s[""] = slurp(p);
    return s;
  }
  s[""] = "<dir>";
  for (const auto& e : fs::recursive_directory_iterator(p)) {
    const std::string rel = fs::relative(e.path(), p).string();
    s[rel] = e.is_directory() ? "<dir>" : slurp(e.path());
  }
  return s;
}

// What a kill may leave beside the outputs: io::files' ".NAME.tmp-PID-N[.ext]" files and folders
// (and replace_directory's ".NAME.tmp-PID-N.old"); the bag writer uses them too.
bool is_temporary(const std::string& name) {
  return name.size() > 1 && name[0] == '.' && name.find(".tmp-") != std::string::npos;
}

// Starts the CLI with `args` in folder `cwd`, stdout and stderr to `log`. Everything the child
// needs is prepared before fork(): after it, only async-signal-safe calls.
pid_t spawn(const std::vector<std::string>& args, const fs::path& cwd, const fs::path& log) {
  std::vector<std::string> argv_s{cropsight::testing::cli_path().string()};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string dir = cwd.string(), log_s = log.string();
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fd = ::open(log_s.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int null = ::open("/dev/null", O_RDONLY);
    if (fd < 0 || null < 0 || ::chdir(dir.c_str()) != 0) ::_exit(126);
    ::dup2(null, 0);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  if (pid < 0) throw std::runtime_error("fork failed");
  return pid;
}

int wait_for(pid_t pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return status;
}

class KillSafety : public ::testing::TestWithParam<Case> {
 protected:
  // The inputs every case reads, made once: a simulated sequence with labels (4 frames: training
  // finds heads and other clusters in it) and its bag.
  static void SetUpTestSuite() {
    inputs_ = new TempDir;
    seq_ = (inputs_->path() / "seq").string();
    bag_ = (inputs_->path() / "seq.bag").string();
    const auto sim = cropsight::testing::run_cli("simulate broccoli --frames 4 --seed 5 --out '" + seq_ + "' --json");
    ASSERT_EQ(sim.exit_code, 0) << sim.err;
    const auto bag = cropsight::testing::run_cli("export --data '" + seq_ + "' --out '" + bag_ + "' --json");
    ASSERT_EQ(bag.exit_code, 0) << bag.err;
    // The CLI's start-up (loading its ~230 shared libraries, about 0.5 s) is part of every run and
    // writes nothing: the kill moments are spread over the rest of the run. The fastest of three
    // runs of --help, so that a busy machine does not push every moment past the work.
    startup_s_ = 1e9;
    for (int i = 0; i < 3; ++i) {
      const auto t0 = Clock::now();
      const int status = wait_for(spawn({"--help"}, inputs_->path(), inputs_->path() / "help.log"));
      ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
      startup_s_ = std::min(startup_s_, std::chrono::duration<double>(Clock::now() - t0).count());
    }
  }
  static void TearDownTestSuite() {
    delete inputs_;
    inputs_ = nullptr;
  }

  static inline TempDir* inputs_ = nullptr;
  static inline std::string seq_, bag_;
  static inline double startup_s_ = 0;
};

// The arguments with the inputs' paths filled in (@SEQ, @BAG).
std::vector<std::string> expand(std::vector<std::string> args, const std::string& seq, const std::string& bag) {
  for (auto& a : args) {
    if (a == "@SEQ") a = seq;
    if (a == "@BAG") a = bag;
  }
  return args;
}

TEST_P(KillSafety, NothingPartialUnderAFinalNameAndTheRerunSucceeds) {
  const Case& c = GetParam();
  const std::vector<std::string> args = expand(c.args, seq_, bag_);
  TempDir work;
  const fs::path logs = work / "logs";
  fs::create_directories(logs);

  // The clean run: its outputs are the reference, its wall time the span of the kill moments.
  const fs::path clean = work / "clean";
  fs::create_directories(clean);
  const auto t0 = Clock::now();
  const int clean_status = wait_for(spawn(args, clean, logs / "clean.log"));
  const double run_s = std::chrono::duration<double>(Clock::now() - t0).count();
  ASSERT_TRUE(WIFEXITED(clean_status) && WEXITSTATUS(clean_status) == 0) << slurp(logs / "clean.log");
  std::map<std::string, Snapshot> reference;
  for (const auto& out : c.outputs) {
    auto s = snapshot(clean / out);
    ASSERT_TRUE(s) << c.name << ": the clean run wrote no " << out;
    reference[out] = std::move(*s);
  }

  // Moments: one per equal slice of [start-up, run time] (from half the run time when start-up
  // took longer than that), at a seeded random point within the slice.
  std::mt19937 rng(26 + std::hash<std::string>{}(c.name) % 1000);
  const double from = std::min(startup_s_, 0.5 * run_s);
  int kills = 0, killed = 0, left_temporaries = 0;
  // A busy machine can make a killed run faster than the clean one, so that every kill comes after
  // the end: then one more, in the middle of start-up, so that at least one kill hit a running
  // command (kill k == c.kills).
  for (int k = 0; k < c.kills || (k == c.kills && killed == 0); ++k) {
    const double at_s = k < c.kills
                            ? from + (run_s - from) * (k + std::uniform_real_distribution<double>(0, 1)(rng)) / c.kills
                            : 0.5 * std::min(startup_s_, run_s);
    const bool replacing = k % 2 == 1;
    ++kills;
    const fs::path dir = work / ("kill-" + std::to_string(k));
    fs::create_directories(dir);
    if (replacing)
      for (const auto& out : c.outputs) fs::copy(clean / out, dir / out, fs::copy_options::recursive);
    const std::string what = c.name + ", kill " + std::to_string(k) + " at " + std::to_string(at_s) + " s of " +
                             std::to_string(run_s) + " s" + (replacing ? " (replacing an earlier output)" : "");

    const pid_t pid = spawn(args, dir, logs / ("kill-" + std::to_string(k) + ".log"));
    std::this_thread::sleep_for(std::chrono::duration<double>(at_s));
    ::kill(pid, SIGKILL);  // a child that already exited is a zombie until waited for: no other process
    const int status = wait_for(pid);
    if (WIFSIGNALED(status)) {
      EXPECT_EQ(WTERMSIG(status), SIGKILL) << what << ": died of another signal before the kill";
      ++killed;
    } else {
      EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0)
          << what << ": finished before the kill, but failed: " << slurp(logs / ("kill-" + std::to_string(k) + ".log"));
    }

    auto check_folder = [&](const std::string& when) {
      for (const auto& out : c.outputs) {
        const auto s = snapshot(dir / out);
        if (s) {
          EXPECT_TRUE(*s == reference[out]) << what << ", " << when << ": " << out << " differs from the clean run's";
        } else {
          // A replacement swaps the new output in (rename, or io::replace_directory's exchange of
          // folders): the earlier output stays visible until then.
          EXPECT_FALSE(replacing) << what << ", " << when << ": the earlier " << out << " is gone";
        }
      }
      for (const auto& e : fs::directory_iterator(dir)) {
        const std::string name = e.path().filename().string();
        const bool output = std::find(c.outputs.begin(), c.outputs.end(), name) != c.outputs.end();
        EXPECT_TRUE(output || is_temporary(name)) << what << ", " << when << ": left '" << name << "'";
      }
    };
    check_folder("after the kill");
    for (const auto& e : fs::directory_iterator(dir)) left_temporaries += is_temporary(e.path().filename().string());

    // The same command again, over whatever the kill left.
    const fs::path rerun_log = logs / ("rerun-" + std::to_string(k) + ".log");
    const int rerun = wait_for(spawn(args, dir, rerun_log));
    EXPECT_TRUE(WIFEXITED(rerun) && WEXITSTATUS(rerun) == 0) << what << ": the rerun failed: " << slurp(rerun_log);
    for (const auto& out : c.outputs)
      EXPECT_TRUE(snapshot(dir / out).has_value()) << what << ": the rerun wrote no " << out;
    check_folder("after the rerun");
    // Folder outputs' writers (io::TempDirectory, io::SequenceWriter) remove the temporaries that
    // killed runs left, so that kills do not pile up partial copies.
    for (const auto& out : c.outputs) {
      if (!fs::is_directory(dir / out)) continue;
      for (const auto& e : fs::directory_iterator(dir)) {
        const std::string name = e.path().filename().string();
        EXPECT_FALSE(name.rfind("." + out + ".", 0) == 0 && is_temporary(name))
            << what << ": the rerun left the killed run's '" << name << "'";
      }
    }
  }
  // Temporaries left show that kills landed while outputs were being written, not only during
  // start-up.
  std::printf("kill: %s: run %.2f s (start-up %.2f s), %d kills, %d while running, %d temporaries left\n",
              c.name.c_str(), run_s, startup_s_, kills, killed, left_temporaries);
  EXPECT_GE(killed, 1) << c.name << ": every run finished before its kill";
}

const std::string kModel = CROPSIGHT_SOURCE_DIR "/models/broccoli-oes-uk.json";

INSTANTIATE_TEST_SUITE_P(
    Commands, KillSafety,
    // --force everywhere: a run replaces the earlier complete output of the same command.
    ::testing::Values(Case{"detect_broccoli",
                           {"detect", "broccoli", "--data", "@SEQ", "--model", kModel, "--out", "out.jsonl", "--masks",
                            "masks", "--track", "--map", "map.csv", "--quiet", "--force"},
                           {"out.jsonl", "masks", "map.csv"}},
                      // --force: a kill after the rename leaves a complete sequence, which the rerun replaces.
                      Case{"simulate_broccoli",
                           {"simulate", "broccoli", "--frames", "3", "--seed", "7", "--out", "sim", "--force"},
                           {"sim"},
                           3},
                      Case{"train_broccoli",
                           {"train", "broccoli", "--data", "@SEQ", "--out", "model.json", "--quiet", "--force"},
                           {"model.json"}},
                      Case{"export_pcd",
                           {"export", "--data", "@SEQ", "--frame", "0", "--out", "frame.pcd", "--force"},
                           {"frame.pcd"}},
                      Case{"export_bag", {"export", "--data", "@SEQ", "--out", "seq.bag", "--force"}, {"seq.bag"}},
                      Case{"import_bag", {"import", "--data", "@BAG", "--out", "imported", "--force"}, {"imported"}}),
    [](const ::testing::TestParamInfo<Case>& info) { return info.param.name; });

}  // namespace
