// harvest potato end to end: a simulated approach (one potato in front of the white sheet) goes
// through the whole loop with the shipped preset; every frame gives one message, the target keeps
// one id, and its position lies near the simulator's truth. Bad input: one line, exit 2, no output.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "testing/testing.hpp"

namespace {
namespace fs = std::filesystem;
using cropsight::testing::run_cli;
using cropsight::testing::shell_quoted;
using cropsight::testing::TempDir;

std::vector<nlohmann::json> read_lines(const fs::path& p) {
  std::vector<nlohmann::json> out;
  std::ifstream in(p);
  for (std::string line; std::getline(in, line);) out.push_back(nlohmann::json::parse(line));
  return out;
}
}  // namespace

TEST(PotatoHarvestCli, SimulatedApproachGivesOneMessagePerFrameAndKeepsTheTarget) {
  TempDir tmp;
  const fs::path seq = tmp.path() / "seq", out = tmp.path() / "targets.jsonl";
  ASSERT_EQ(
      run_cli("simulate potato --scene sheet --frames 12 --seed 4242 --out " + shell_quoted(seq.string())).exit_code,
      0);
  const auto r = run_cli("harvest potato --data " + shell_quoted(seq.string()) + " --out " +
                         shell_quoted(out.string()) + " --json --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto summary = nlohmann::json::parse(r.out);
  EXPECT_EQ(summary["frames"], 12);
  const auto lines = read_lines(out);
  ASSERT_EQ(lines.size(), 12u);
  int with_target = 0, with_depth = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const auto& m = lines[i];
    EXPECT_EQ(m["frame"], int(i));
    for (const char* k : {"detection", "depth_ok", "x", "y", "z", "height", "width", "angle", "target_id", "state"})
      EXPECT_TRUE(m.contains(k)) << k;
    if (!m["detection"].get<bool>()) continue;
    ++with_target;
    EXPECT_EQ(m["target_id"], 1) << "the target switched at frame " << i;
    // The approach runs at 0.3-0.5 m (depth_ok is false once the surface comes under the D415's
    // 0.25 m) and the angle is in [0, pi).
    if (m["depth_ok"].get<bool>()) {
      ++with_depth;
      EXPECT_GT(m["z"].get<double>(), 0.2);
      EXPECT_LT(m["z"].get<double>(), 0.8);
    } else {
      EXPECT_EQ(m["z"].get<double>(), 0.0);
    }
    EXPECT_GE(m["angle"].get<double>(), 0.0);
    EXPECT_LT(m["angle"].get<double>(), M_PI);
  }
  EXPECT_GE(with_target, 10);
  EXPECT_GE(with_depth, 9);
}

TEST(PotatoHarvestCli, BadInputIsOneLineAndNoOutput) {
  TempDir tmp;
  const fs::path out = tmp.path() / "t.jsonl";
  auto r = run_cli("harvest potato --data " + shell_quoted((tmp.path() / "missing").string()) + " --out " +
                   shell_quoted(out.string()));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("missing"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  r = run_cli("harvest potato --data " + shell_quoted(tmp.path().string()) + " --set tracking.epsilon_px=-1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("'tracking.epsilon_px' must be greater than 0"), std::string::npos) << r.err;
  r = run_cli("harvest potato --data " + shell_quoted(tmp.path().string()) + " --set detector.backend=onnx");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("detector.onnx.model"), std::string::npos) << r.err;
}
