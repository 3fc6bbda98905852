// cropsight batch --engine slurm against a real Slurm: the one-node cluster of
// scripts/slurm-local.sh (munged, slurmctld, slurmd on this machine). Skips with a message when
// no slurmctld answers. Label `slurm` (CMakeLists.txt); CI starts the cluster before `make test`.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <regex>

#include "batch_fixture.hpp"

namespace cropsight::batch_test {

namespace {

// Slurm's commands find the cluster through SLURM_CONF; slurm-local.sh's default folder when unset.
bool slurm_answers() {
  const char* conf = std::getenv("SLURM_CONF");
  if (!conf && fs::exists("/tmp/cropsight-slurm/slurm.conf"))
    setenv("SLURM_CONF", "/tmp/cropsight-slurm/slurm.conf", 1);
  return std::system("scontrol ping 2>/dev/null | grep -q 'is UP'") == 0;
}

std::string command_output(const std::string& cmd) {
  std::string out;
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  char buf[4096];
  for (std::size_t n; p && (n = fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
  if (p) pclose(p);
  return out;
}

std::string first_job_id(const std::string& json) {
  std::smatch m;
  return std::regex_search(json, m, std::regex("\"jobs\":\\[\"([0-9]+)\"")) ? m[1].str() : "";
}

}  // namespace

class BatchSlurm : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (!slurm_answers()) return;
    tmp_ = new cropsight::testing::TempDir();
    error_ = shared_passes(passes_);
    const fs::path m = write_manifest(tmp_->path() / "m.yaml", pass_paths(passes_));
    const auto r = run_cli("batch --quiet --manifest " + shell_quoted(m) + " --out " + shell_quoted(local()));
    if (error_.empty() && r.exit_code != 0) error_ = "local batch: " + r.err;
  }
  static void TearDownTestSuite() { delete tmp_; }
  void SetUp() override {
    if (!tmp_) GTEST_SKIP() << "no slurmctld answers (start one with: sudo scripts/slurm-local.sh start)";
    if (!error_.empty()) GTEST_FAIL() << error_;
  }
  static fs::path dir() { return tmp_->path(); }
  static fs::path local() { return dir() / "local"; }
  std::string batch_args(const fs::path& manifest, const fs::path& out) const {
    return "batch --engine slurm --mem 500M --poll 0.3 --manifest " + shell_quoted(manifest) + " --out " +
           shell_quoted(out);
  }
  static cropsight::testing::TempDir* tmp_;
  static fs::path passes_;
  static std::string error_;
};
cropsight::testing::TempDir* BatchSlurm::tmp_ = nullptr;
fs::path BatchSlurm::passes_;
std::string BatchSlurm::error_;

TEST_F(BatchSlurm, SeedlingRowsEqualLocal) {
  // A crop whose results are rows, not a map: the array tasks write the same rows as local workers.
  for (int seed : {1, 2})
    ASSERT_EQ(run_cli("simulate seedling --pairs 2 --calib-pairs 0 --seed " + std::to_string(seed) + " --out " +
                      shell_quoted(dir() / ("seedling-" + std::to_string(seed))))
                  .exit_code,
              0);
  cropsight::testing::write_text(dir() / "seedlings.csv", "recording,crop\nseedling-1,seedling\nseedling-2,\n");
  const auto local_run = run_cli("batch --quiet --manifest " + shell_quoted(dir() / "seedlings.csv") + " --out " +
                                 shell_quoted(dir() / "seedling-local"));
  ASSERT_EQ(local_run.exit_code, 0) << local_run.err;
  const auto r = run_cli(batch_args(dir() / "seedlings.csv", dir() / "seedling-slurm") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_EQ(json_number(r.out, "ran"), 2);
  EXPECT_EQ(slurp(dir() / "seedling-slurm" / "seedlings.csv"), slurp(dir() / "seedling-local" / "seedlings.csv"));
  EXPECT_NE(slurp(dir() / "seedling-slurm" / "seedlings.csv").find("seedling-2,seedling-2,1,pair_"), std::string::npos);
}

TEST_F(BatchSlurm, MergedMapEqualsLocalAndSchedulerListsTheArrayTasks) {
  const fs::path out = dir() / "slurm";
  const auto r = run_cli(batch_args(dir() / "m.yaml", out) + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_EQ(json_number(r.out, "ran"), 4);
  EXPECT_EQ(slurp(out / "field-map.csv"), slurp(local() / "field-map.csv"));
  EXPECT_EQ(slurp(out / "field-map.geojson"), slurp(local() / "field-map.geojson"));
  const std::string job = first_job_id(r.out);
  ASSERT_FALSE(job.empty()) << r.out;
  const std::string shown = command_output("scontrol show job " + job);
  for (int task = 0; task < 4; ++task)
    EXPECT_TRUE(std::regex_search(shown, std::regex("ArrayJobId=" + job + " ArrayTaskId=" + std::to_string(task) +
                                                    "[\\s\\S]*?JobState=COMPLETED")))
        << shown;
  EXPECT_NE(slurp(out / "slurm" / "batch.sbatch").find("batch-shard --batch-dir"), std::string::npos);
}

TEST_F(BatchSlurm, TaskThatFailsOnceIsResubmittedAndTheBatchCompletes) {
  // The injected fault: one frame of pass2 unreadable until its first attempt has failed (in a
  // copy: the shared passes are never modified).
  fs::create_directories(dir() / "fault");
  fs::copy(passes_ / "pass2", dir() / "fault" / "pass2", fs::copy_options::recursive);
  auto recordings = pass_paths(passes_);
  recordings[1] = dir() / "fault" / "pass2";
  const fs::path manifest = write_manifest(dir() / "m-fault.yaml", recordings);
  const fs::path frame = dir() / "fault" / "pass2" / "depth" / "000003.png";
  const std::string good = slurp(frame);
  cropsight::testing::write_text(frame, "not a PNG");
  const fs::path out = dir() / "slurm-fault", log = dir() / "fault.log";
  const pid_t pid = start_cli(batch_args(manifest, out) + " --json", log);
  const bool failed_once = wait_for(
      [&] {
        std::error_code ec;
        for (const auto& e : fs::directory_iterator(out / "slurm" / "logs", ec))
          if (slurp(e.path()).find("cropsight: ") != std::string::npos) return true;
        return false;
      },
      120);
  std::ofstream(frame, std::ios::binary) << good;  // the recording is readable again
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(failed_once) << "no task failed: " << slurp(log);
  const std::string summary = slurp(log);
  ASSERT_EQ(WEXITSTATUS(status), 0) << summary;
  EXPECT_GE(json_number(summary, "resubmitted"), 1) << summary;
  EXPECT_EQ(json_number(summary, "failed"), 0) << summary;
  EXPECT_EQ(slurp(out / "field-map.csv"), slurp(local() / "field-map.csv"));
}

TEST_F(BatchSlurm, InterruptedBatchRestartedRunsOnlyTheRest) {
  // One task at a time (the array throttle), so that the interruption falls between shards.
  const fs::path m = write_manifest(dir() / "m-throttled.yaml", pass_paths(passes_), "slurm: {max_parallel: 1}\n");
  const fs::path out = dir() / "slurm-killed", log = dir() / "killed.log";
  const pid_t pid = start_cli(batch_args(m, out), log);
  ASSERT_TRUE(wait_for([&] { return done_shards(out) >= 2; }, 120)) << slurp(log);
  kill(-pid, SIGKILL);
  waitpid(pid, nullptr, 0);
  std::smatch job;
  const std::string text = slurp(log);
  ASSERT_TRUE(std::regex_search(text, job, std::regex("job ([0-9]+):"))) << text;
  std::system(("scancel " + job[1].str()).c_str());  // the batch and its job both stopped
  ASSERT_TRUE(wait_for([&] { return command_output("squeue -h -j " + job[1].str()).empty(); }, 60));
  const int done = done_shards(out);
  EXPECT_EQ(incomplete_visible_shards(out), 0);
  const auto r = run_cli(batch_args(m, out) + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_EQ(json_number(r.out, "already_done"), done);
  EXPECT_EQ(json_number(r.out, "ran"), 4 - done);
  EXPECT_LT(done, 4) << "the interruption came too late to test anything";
  EXPECT_EQ(slurp(out / "field-map.csv"), slurp(local() / "field-map.csv"));
}

TEST_F(BatchSlurm, BadManifestFailsBeforeSubmission) {
  const std::string before = command_output("squeue -h -o %i");
  write_manifest(dir() / "bad.yaml", {passes_ / "pass1", dir() / "missing"});
  const auto r = run_cli(batch_args(dir() / "bad.yaml", dir() / "never"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(dir() / "never"));
  EXPECT_EQ(command_output("squeue -h -o %i"), before);  // nothing was submitted
}

}  // namespace cropsight::batch_test
