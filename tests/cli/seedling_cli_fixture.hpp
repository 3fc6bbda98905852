#pragma once
// What the stereo / seedling CLI suites share: one simulated seedling data set per suite, made
// once in a temporary folder (`Suite::kSimulateArgs`: its `simulate seedling` options), the paths
// into it, and the CLI's error contract.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "testing/testing.hpp"

template <class Suite>
class SeedlingCliFixture : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    tmp_ = new cropsight::testing::TempDir;
    sim_ok_ = cropsight::testing::run_cli("simulate seedling --out " + cropsight::testing::shell_quoted(data()) +
                                          Suite::kSimulateArgs)
                  .exit_code == 0;
  }
  static void TearDownTestSuite() {
    delete tmp_;
    tmp_ = nullptr;
  }
  void SetUp() override { ASSERT_TRUE(sim_ok_) << "simulate seedling failed"; }
  static std::filesystem::path dir() { return tmp_->path(); }
  static std::filesystem::path data() { return *tmp_ / "pairs"; }
  static std::filesystem::path pair0() { return data() / "pair_000"; }
  // The error contract: exit 2, exactly one line on stderr that names `what`.
  static void expect_one_line_error(const cropsight::testing::CommandResult& r, const std::string& what) {
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(what), std::string::npos) << "expected '" << what << "' in: " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }

 private:
  static inline cropsight::testing::TempDir* tmp_ = nullptr;  // one data set per suite (template)
  static inline bool sim_ok_ = false;
};
