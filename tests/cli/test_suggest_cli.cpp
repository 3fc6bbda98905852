// CLI tests of `cropsight suggest` and of `train broccoli --frame-list / --extra-data`, the two halves
// of labelling a few frames of one's own field: the ranking as JSON and text, training on only the
// chosen frames, and every bad input as one line with exit 2 and nothing written.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>

#include "cropsight/io/sequence.hpp"
#include "cropsight/learning/model.hpp"
#include "one_line_error.hpp"
#include "testing/testing.hpp"

namespace fs = std::filesystem;
using namespace cropsight;
using cropsight::testing::run_cli;
using cropsight::testing::shell_quoted;

namespace suggest_cli_test {
class SuggestCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    tmp_ = new cropsight::testing::TempDir;
    // The uk field of the simulator, 8 frames: heads and leaves enough to rank and to train on.
    ASSERT_EQ(run_cli("simulate broccoli --frames 8 --seed 23 --quiet --out " + shell_quoted(seq())).exit_code, 0);
  }
  static void TearDownTestSuite() {
    delete tmp_;
    tmp_ = nullptr;
  }
  static fs::path seq() { return *tmp_ / "seq"; }
  static fs::path dir() { return tmp_->path(); }
  static cropsight::testing::TempDir* tmp_;
};
cropsight::testing::TempDir* SuggestCli::tmp_ = nullptr;

using cropsight::testing::expect_one_line_error;
}  // namespace suggest_cli_test

using suggest_cli_test::SuggestCli;

TEST_F(SuggestCli, RanksFramesAsJsonAndText) {
  auto r = run_cli("suggest --data " + shell_quoted(seq()) + " --frames 3 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["frames"].size(), 3u);
  ASSERT_EQ(j["scores"].size(), 3u);
  EXPECT_EQ(j["total_frames"], 8);
  std::set<int> distinct;
  for (const auto& f : j["frames"]) {
    EXPECT_TRUE(f.get<int>() >= 0 && f.get<int>() < 8);
    distinct.insert(f.get<int>());
  }
  EXPECT_EQ(distinct.size(), 3u);
  EXPECT_GE(j["scores"][0].get<double>(), j["scores"][1].get<double>()) << "best first";

  r = run_cli("suggest --data " + shell_quoted(seq()) + " --frames 20 --json --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["frames"].size(), 8u) << "at most every frame, once";

  r = run_cli("suggest --data " + shell_quoted(seq()) + " --frames 2 --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("label these 2 of 8 frames"), std::string::npos) << r.out;
}

TEST_F(SuggestCli, BadInputIsOneLine) {
  expect_one_line_error(run_cli("suggest --data " + shell_quoted(dir() / "nope") + " --frames 3"), "nope");
  expect_one_line_error(run_cli("suggest --data " + shell_quoted(seq()) + " --frames 0"), "--frames");
  expect_one_line_error(run_cli("suggest --data " + shell_quoted(seq()) + " --diversity 2"), "--diversity");
  expect_one_line_error(run_cli("suggest --data " + shell_quoted(seq()) + " --heads-weight -1"), "--heads-weight");
  expect_one_line_error(run_cli("suggest --data " + shell_quoted(seq()) + " --model " + shell_quoted(dir() / "m.json")),
                        "m.json");
}

TEST_F(SuggestCli, TrainsOnTheChosenFramesOnly) {
  const fs::path model = dir() / "chosen.json";
  auto r = run_cli("train broccoli --data " + shell_quoted(seq()) +
                   " --frame-list 5,1,5 --config broccoli-oes-uk --quiet --json --out " + shell_quoted(model));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["frames"], 2) << "repeats count once";
  const learning::Model m = learning::load_model(model);
  EXPECT_EQ(m.info.provenance.at("chosen_frames"), "5,1,5");
  EXPECT_EQ(m.info.provenance.at("frames"), "2");

  // --extra-data: the same frames plus a whole second pass (here the same sequence again).
  const fs::path both = dir() / "both.json";
  r = run_cli("train broccoli --data " + shell_quoted(seq()) + " --frame-list 1 --extra-data " + shell_quoted(seq()) +
              " --config broccoli-oes-uk --quiet --json --out " + shell_quoted(both));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["frames"], 9);
}

TEST_F(SuggestCli, TrainFramesBadInputWritesNothing) {
  const fs::path model = dir() / "bad.json";
  const std::string base = "train broccoli --data " + shell_quoted(seq()) + " --config broccoli-oes-uk --out " +
                           shell_quoted(model) + " --quiet";
  expect_one_line_error(run_cli(base + " --frame-list 8"), "--frame-list");
  expect_one_line_error(run_cli(base + " --frame-list 1,x"), "'x'");
  expect_one_line_error(run_cli(base + " --frame-list -1"), "--frame-list");
  expect_one_line_error(run_cli(base + " --frame-list 1 --fit-size-bias"), "--fit-size-bias");
  expect_one_line_error(run_cli(base + " --frame-list 1 --extra-data " + shell_quoted(dir() / "missing")), "missing");
  EXPECT_FALSE(fs::exists(model));
}
