// bench potato: times the loop per stage on frames it simulates itself (or --data), beside the
// RGB -> Lab baseline of the same process; the JSON names every stage, the stage times add up to
// no more than the frame time, and bad options are one line with exit 2. Speed is not asserted
// here (a timed unit test cannot be trusted on a shared machine): it is the command's output.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "testing/testing.hpp"

namespace {
namespace fs = std::filesystem;
using cropsight::testing::run_cli;
using cropsight::testing::shell_quoted;
using cropsight::testing::TempDir;
}  // namespace

TEST(PotatoBenchCli, TimesEveryStageOfTheLoopOnASimulatedApproach) {
  const auto r = run_cli("bench potato --frames 4 --repeat 1 --json --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["frames"], 4);
  EXPECT_EQ(j["width"], 640);
  EXPECT_EQ(j["height"], 480);
  EXPECT_EQ(j["threads"], 1);
  EXPECT_GT(j["baseline_lab_conversion_ms"].get<double>(), 0.0);
  const auto& p = j["presets"]["potato"];
  double stages = 0;
  for (const char* s : {"detect", "locate", "track", "orient"}) {
    ASSERT_TRUE(p["stages_ms"].contains(s)) << s;
    stages += p["stages_ms"][s].get<double>();
  }
  EXPECT_GT(stages, 0.0);
  EXPECT_LE(stages, p["ms_per_frame"].get<double>() * 1.01 + 0.01);
  EXPECT_GT(p["ratio_to_baseline"].get<double>(), 0.0);
  // The simulated approach has potatoes in view: the loop finds a target (not necessarily at the
  // first frame, which starts the selection), and counts no more frames than it timed.
  EXPECT_GE(p["frames_with_target"].get<int>(), 1);
  EXPECT_LE(p["frames_with_target"].get<int>(), 4);
}

TEST(PotatoBenchCli, ReadsASequenceAndRejectsBadOptions) {
  TempDir tmp;
  const fs::path seq = tmp.path() / "seq";
  ASSERT_EQ(run_cli("simulate potato --frames 2 --seed 5 --out " + shell_quoted(seq.string())).exit_code, 0);
  const auto ok = run_cli("bench potato --data " + shell_quoted(seq.string()) + " --repeat 1 --json");
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_EQ(nlohmann::json::parse(ok.out)["frames"], 2);

  const auto too_many = run_cli("bench potato --data " + shell_quoted(seq.string()) + " --frames 3");
  EXPECT_EQ(too_many.exit_code, 2);
  EXPECT_NE(too_many.err.find("--frames"), std::string::npos) << too_many.err;
  const auto missing = run_cli("bench potato --data " + shell_quoted((tmp.path() / "none").string()));
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("none"), std::string::npos) << missing.err;
  const auto preset = run_cli("bench potato --presets potato,no-such-preset --frames 1");
  EXPECT_EQ(preset.exit_code, 2);
  EXPECT_NE(preset.err.find("no-such-preset"), std::string::npos) << preset.err;
  const auto repeat = run_cli("bench potato --repeat 0");
  EXPECT_EQ(repeat.exit_code, 2);
  EXPECT_NE(repeat.err.find("--repeat"), std::string::npos) << repeat.err;
}
