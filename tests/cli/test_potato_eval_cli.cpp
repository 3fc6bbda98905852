// eval potato end to end: a small simulated approach through the whole loop with the shipped
// preset (the classical detector, not truth boxes), scored against the simulator's truth. Bad
// input: one line naming the file, exit 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "testing/testing.hpp"

namespace {
namespace fs = std::filesystem;
using cropsight::testing::run_cli;
using cropsight::testing::shell_quoted;
using cropsight::testing::TempDir;

fs::path simulate(const TempDir& tmp) {
  const fs::path seq = tmp.path() / "seq";
  const auto r =
      run_cli("simulate potato --scene sheet --frames 12 --seed 4244 --set width=320 --set height=240 --out " +
              shell_quoted(seq.string()) + " --json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return seq;
}
}  // namespace

TEST(PotatoEvalCli, SimulatedApproachIsScoredAgainstTruth) {
  TempDir tmp;
  const fs::path seq = simulate(tmp);
  const auto r = run_cli("eval potato --data " + shell_quoted(seq.string()) + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  // On this seed the nearest potato (the loop's choice) is the one the camera approaches.
  EXPECT_EQ(j["frames"], 12);
  EXPECT_GE(j["frames_on_target"].get<int>(), 11);
  EXPECT_EQ(j["target_switches"], 0);
  EXPECT_EQ(j["lost_events"], 0);
  for (const char* axis : {"x", "y", "z"}) {
    EXPECT_LT(j["position"][axis]["mae_mm"].get<double>(), 5.0) << axis;  // the target
    EXPECT_TRUE(j["position"][axis].contains("std_mm"));
  }
  for (const char* k : {"length_mae_mm", "width_mae_mm", "angle_mae_deg"}) EXPECT_TRUE(j.contains(k)) << k;
  for (const char* k : {"detect", "locate", "track", "orient", "total"})
    EXPECT_GT(j["ms_per_frame"][k].get<double>(), 0.0) << k;
  // Text output names the same figures.
  const auto text = run_cli("eval potato --data " + shell_quoted(seq.string()));
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("position z"), std::string::npos) << text.out;
}

TEST(PotatoEvalCli, BadInputIsOneLineNamingTheFile) {
  TempDir tmp;
  auto r = run_cli("eval potato --data " + shell_quoted((tmp.path() / "missing").string()));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("missing"), std::string::npos) << r.err;
  const fs::path seq = simulate(tmp);
  r = run_cli("eval potato --data " + shell_quoted(seq.string()) + " --set tracking.tracking_limit=-1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("tracking.tracking_limit"), std::string::npos) << r.err;
  fs::remove(seq / "groundtruth.json");
  r = run_cli("eval potato --data " + shell_quoted(seq.string()));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("groundtruth.json"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}
