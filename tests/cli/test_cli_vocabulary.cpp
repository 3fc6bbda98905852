// One vocabulary (docs/cli.md): every command's options, read from its --help, checked against the
// conventions, so that a new command or option that breaks one fails here.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "testing/testing.hpp"

namespace cli_vocabulary {
using cropsight::testing::run_cli;

struct Option {
  std::string name, type;  ///< "--out", "TEXT" ("" for a flag)
};

// The names listed under "Subcommands:" in a --help text.
std::vector<std::string> subcommands(const std::string& help) {
  std::vector<std::string> out;
  std::istringstream in(help);
  bool inside = false;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("Subcommands:", 0) == 0) {
      inside = true;
      continue;
    }
    if (!inside) continue;
    std::smatch m;
    if (std::regex_search(line, m, std::regex(R"(^  ([a-z][a-z0-9-]*))"))) out.push_back(m[1]);
  }
  return out;
}

// The long options of a --help text with their type word (CLI11: "--out TEXT REQUIRED").
std::vector<Option> options(const std::string& help) {
  std::vector<Option> out;
  std::istringstream in(help);
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    if (!std::regex_search(line, m, std::regex(R"(^  (?:-\w,)?(--[a-z0-9-]+)(?: ([A-Z]+))?)"))) continue;
    out.push_back({m[1], m.size() > 2 ? std::string(m[2]) : ""});
  }
  return out;
}

// Every command ("detect broccoli", "info", ...) with its --help text. A verb with options of its
// own besides --help is a command too, sub-commands or not (`report` and `report demo`).
std::map<std::string, std::string> commands() {
  std::map<std::string, std::string> out;
  for (const std::string& verb : subcommands(run_cli("--help").out)) {
    const std::string help = run_cli(verb + " --help").out;
    const auto subs = subcommands(help);
    if (subs.empty() || options(help).size() > 1) out[verb] = help;
    for (const std::string& sub : subs) out[verb + " " + sub] = run_cli(verb + " " + sub + " --help").out;
  }
  return out;
}

TEST(CliVocabulary, EveryCommandFollowsTheConventions) {
  const auto all = commands();
  ASSERT_GT(all.size(), 30u) << "the command tree was not read";
  // Options that hold numbers must be typed as numbers, so that --help and CLI11 say so.
  const std::set<std::string> numeric = {
      "--frames",          "--seed",       "--threads",     "--fps",       "--votes",         "--carry-k",
      "--ensemble-weight", "--pairs",      "--calib-pairs", "--epochs",    "--max-disp",      "--window",
      "--frame",           "--limit",      "--folds",       "--width",     "--batch",         "--lr",
      "--val-split",       "--split-seed", "--image-id",    "--square-mm", "--map-min-points"};
  // Old spellings work for one release but are never shown (docs/cli.md, "Older spellings").
  const std::set<std::string> retired = {"--overwrite", "--bag", "--input"};
  // Commands that print progress lines on stderr: each can be silenced with --quiet.
  const std::set<std::string> with_progress = {
      "simulate broccoli", "simulate potato", "simulate seedling", "detect broccoli", "eval broccoli",
      "train broccoli",    "eval seedling",   "harvest potato",    "report",          "suggest",
      "train grape",       "train detector",  "bench potato"};
  std::string problems;
  for (const std::string& name : with_progress)
    if (!all.count(name)) problems += name + ": no such command (update this test)\n";
  for (const auto& [name, help] : all) {
    std::set<std::string> names;
    for (const Option& o : options(help)) {
      names.insert(o.name);
      if (numeric.count(o.name) && (o.type == "TEXT" || o.type.empty()))
        problems += name + ": " + o.name + " is typed '" + o.type + "', not a number\n";
      if (retired.count(o.name)) problems += name + ": shows the retired option " + o.name + "\n";
    }
    if (std::regex_search(help, std::regex(R"(issue \d)"))) problems += name + ": its help cites an issue number\n";
    if (names.count("--out") && !names.count("--force")) problems += name + ": writes --out but has no --force\n";
    if (with_progress.count(name) && !names.count("--quiet"))
      problems += name + ": prints progress but has no --quiet\n";
    // A sequence or bag is --data, images --images, point clouds --clouds: no other input name.
    for (const char* other : {"--seq", "--sequence", "--input-dir", "--cloud", "--image-dir"})
      if (names.count(other)) problems += name + ": " + other + " is not in the vocabulary\n";
  }
  EXPECT_EQ(problems, "");
}

TEST(CliVocabulary, OldSpellingsStillWorkWithOneDeprecationLine) {
  cropsight::testing::TempDir t;
  const auto seq = cropsight::testing::shell_quoted(t / "seq");
  ASSERT_EQ(run_cli("simulate broccoli --frames 1 --quiet --out " + seq).exit_code, 0);
  const auto r = run_cli("info " + seq + " --json");  // the positional sequence of earlier releases
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("deprecated"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--data"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  const auto old = run_cli("calibrate-detector --help");
  EXPECT_EQ(old.exit_code, 0);
  EXPECT_NE(old.err.find("tune-mask-thresholds"), std::string::npos) << old.err;
}

}  // namespace cli_vocabulary
