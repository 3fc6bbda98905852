// cropsight studio's bad input: one line naming the input, exit 2, and no lock file left behind.
#include <gtest/gtest.h>

#include "studio_fixture.hpp"

namespace cropsight::studio_testing {

namespace fs = std::filesystem;

TEST(StudioCli, BadInputIsOneLineAndExit2) {
  testing::TempDir dir;
  const fs::path seq = unlabelled_copy(dir.path());
  // A port that is taken: a studio holds it while the CLI tries it.
  RunningStudio holder({.sequence = seq, .read_only = true});
  const std::string port = std::to_string(holder.server().port());
  fs::create_directory(dir / "other");
  const fs::path unlabelled = unlabelled_copy(dir / "other");  // a pass without labels/
  const std::vector<std::pair<std::string, std::string>> cases{
      {"--data " + testing::shell_quoted(dir / "missing"), "sequence directory not found"},
      {"--data " + testing::shell_quoted(seq / "camera.yaml"), "not a directory"},
      {"--data " + testing::shell_quoted(seq) + " --model no-such-model", "no-such-model"},
      {"--data " + testing::shell_quoted(seq) + " --port " + port, "cannot listen"},
      {"--data " + testing::shell_quoted(seq) + " --port 70000", "70000"},
      {"--data " + testing::shell_quoted(seq) + " --general-data " + testing::shell_quoted(dir / "missing"),
       "sequence directory not found"},
      {"--data " + testing::shell_quoted(seq) + " --general-data " + testing::shell_quoted(seq), "own sequence"},
      {"--data " + testing::shell_quoted(seq) + " --general-data " + testing::shell_quoted(unlabelled),
       "has no labels"}};
  for (const auto& [args, words] : cases) {
    const auto r = testing::run_cli("studio " + args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(words), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(seq / ".cropsight-studio.lock")) << args;
  }
}

TEST(StudioCli, BadImageFolderIsOneLineAndExit2) {
  testing::TempDir dir;
  const fs::path seq = unlabelled_copy(dir.path());
  fs::create_directories(dir / "empty");
  fs::create_directories(dir / "images" / "cropsight-labels");
  fs::copy_file(seq / "depth" / "000000.png", dir / "images" / "a.png");
  fs::copy_file(seq / "depth" / "000001.png", dir / "images" / "a.jpg");  // same stem, decoded only when opened
  const std::vector<std::pair<std::string, std::string>> cases{
      {"--images " + testing::shell_quoted(dir / "missing"), "missing"},
      {"--images " + testing::shell_quoted(dir / "empty"), "no .jpg or .png"},
      {"--images " + testing::shell_quoted(dir / "images"), "stem 'a'"},
      {"--data " + testing::shell_quoted(seq) + " --images " + testing::shell_quoted(dir / "empty"), "exactly one"},
      {"", "exactly one"},
      {"--data " + testing::shell_quoted(seq) + " --detector detector-grape", "--images only"},
      {"--images " + testing::shell_quoted(dir / "empty") + " --general-data " + testing::shell_quoted(seq),
       "not --images"},
      {"--images " + testing::shell_quoted(dir / "empty") + " --detector no-such-detector", "no-such-detector"}};
  for (const auto& [args, words] : cases) {
    const auto r = testing::run_cli("studio " + args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(words), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  fs::remove(dir / "images" / "a.jpg");
  const auto r = testing::run_cli("studio --images " + testing::shell_quoted(dir / "images"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("not written by cropsight studio"), std::string::npos) << r.err;
  for (const char* name : {"empty", "images"}) EXPECT_FALSE(fs::exists(dir / name / ".cropsight-studio.lock")) << name;
}

}  // namespace cropsight::studio_testing
