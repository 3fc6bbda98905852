// `make demo` end to end: scripts/demo.sh runs the five systems into a temporary folder (a
// broccoli pass of 8 frames instead of 30, to save time) and writes the page with
// `cropsight report demo`; the page is then opened in headless Chromium, which must find the five
// chapters, each opening with its picture, and must have decoded every <img> and every image
// inside an <svg> and laid out every <svg>. Skipped with a message when Chromium is not installed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "chromium_check.hpp"
#include "testing/testing.hpp"

namespace fs = std::filesystem;

namespace demo_page_test {

using cropsight::testing::capture;
using cropsight::testing::chromium_path;
using cropsight::testing::render_check;

}  // namespace demo_page_test

TEST(DemoPage, TheDemoWritesFiveChaptersThatChromiumRenders) {
  using namespace demo_page_test;
  cropsight::testing::TempDir tmp;
  const fs::path build = cropsight::testing::cli_path().parent_path().parent_path();
  const fs::path demo = tmp / "demo";
  const std::string log =
      capture("cd " + cropsight::testing::shell_quoted(cropsight::testing::source_dir()) +
              " && DEMO_BROCCOLI_FRAMES=8 scripts/demo.sh " + cropsight::testing::shell_quoted(build) + " " +
              cropsight::testing::shell_quoted(demo) + " 2>&1; echo \"exit $?\"");
  ASSERT_NE(log.find("exit 0"), std::string::npos) << log;
  const fs::path page = demo / "index.html";
  ASSERT_TRUE(fs::exists(page)) << log;
  EXPECT_NE(log.find(fs::absolute(page).lexically_normal().string()), std::string::npos) << log;
  std::ifstream in(page);
  const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(html.find("src=\"http"), std::string::npos);  // self-contained: nothing fetched
  EXPECT_EQ(html.find("href=\"http"), std::string::npos);
  EXPECT_EQ(html.find("<script"), std::string::npos);

  const std::string chromium = chromium_path();
  if (chromium.empty()) GTEST_SKIP() << "chromium not installed (command -v chromium): the page was not opened";
  const nlohmann::json r = render_check(chromium, page, tmp.path());
  ASSERT_TRUE(r.is_object()) << "chromium gave no render check";
  EXPECT_EQ(r["bad"], nlohmann::json::array()) << r.dump();
  EXPECT_GE(r["imgs"].get<int>(), 4) << r.dump();        // the broccoli frames and the sequence's
  EXPECT_GE(r["svg_images"].get<int>(), 4) << r.dump();  // one picture per other chapter
  const std::vector<std::string> ids = {"broccoli", "seedling", "potato", "grape", "detector"};
  ASSERT_EQ(r["chapters"].size(), ids.size()) << r.dump();
  for (std::size_t i = 0; i < ids.size(); ++i) {
    EXPECT_EQ(r["chapters"][i]["id"], ids[i]);
    EXPECT_TRUE(r["chapters"][i]["picture_first"].get<bool>()) << ids[i] << " does not open with its picture";
  }
}

TEST(DemoPage, ReportDemoRefusesMissingSectionsBeforeWritingAnything) {
  using cropsight::testing::run_cli;
  using cropsight::testing::shell_quoted;
  cropsight::testing::TempDir tmp;
  fs::create_directories(tmp / "grape");
  const fs::path page = tmp / "page.html";
  auto r = run_cli("report demo --out " + shell_quoted(page));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--broccoli"), std::string::npos) << r.err;
  r = run_cli("report demo --grape " + shell_quoted(tmp / "grape") + " --out " + shell_quoted(page));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("truth.json"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(page));
  // `report` itself still needs its sequence and its page, now checked by the command.
  r = run_cli("report --out " + shell_quoted(page));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--data"), std::string::npos) << r.err;
}
