// The output rule (io/output.hpp): what may be written, replaced or never touched.
#include "cropsight/io/output.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "cropsight/core/error.hpp"
#include "testing/testing.hpp"

// A named namespace: the tests compile as unity batches, where another file's helpers would meet.
namespace output_test {
using cropsight::testing::error_message;
namespace fs = std::filesystem;
using cropsight::Error;
using cropsight::io::OutputFolder;
using cropsight::io::OutputPolicy;
using cropsight::testing::TempDir;

// A fixture file, with the folders above it.
void write_text(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  cropsight::testing::write_text(p, text);
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

size_t entries(const fs::path& dir) { return size_t(std::distance(fs::directory_iterator(dir), {})); }

TEST(OutputFolder, NewFolderGetsTheMarkerListingItsFiles) {
  TempDir t;
  {
    OutputFolder out(t / "a/b/out", {"detect potato", false, {}});
    write_text(out.path() / "x.txt", "1");
    fs::create_directory(out.path() / "sub");
    write_text(out.path() / "sub/y.txt", "2");
    EXPECT_FALSE(fs::exists(t / "a/b/out"));  // nothing at the final name until commit
    out.commit();
  }
  const auto m = cropsight::io::read_output_marker(t / "a/b/out");
  ASSERT_TRUE(m.present);
  EXPECT_EQ(m.command, "detect potato");
  EXPECT_EQ(m.entries, (std::vector<std::string>{"sub", "sub/y.txt", "x.txt"}));
  EXPECT_EQ(entries(t / "a/b"), 1u);  // no temporary left beside it
}

TEST(OutputFolder, FailedRunLeavesNothingNotEvenTheParentsItCreated) {
  TempDir t;
  {
    OutputFolder out(t / "new/deeper/out", {"x", false, {}});
    write_text(out.path() / "x.txt", "1");
  }  // no commit: an error unwound the run
  EXPECT_EQ(entries(t.path()), 0u);
}

TEST(OutputFolder, AUserFolderIsNeverReplacedForceOrNot) {
  TempDir t;
  write_text(t / "mine/notes.md", "my notes");
  for (bool force : {false, true}) {
    const std::string e = error_message([&] { OutputFolder out(t / "mine", {"detect potato", force, {}}); });
    EXPECT_NE(e.find("not written by cropsight"), std::string::npos) << e;
    EXPECT_EQ(slurp(t / "mine/notes.md"), "my notes");
    EXPECT_EQ(entries(t.path()), 1u);
  }
}

TEST(OutputFolder, EmptyFolderIsUsed) {
  TempDir t;
  fs::create_directory(t / "empty");
  OutputFolder out(t / "empty", {"x", false, {}});
  write_text(out.path() / "a.txt", "a");
  out.commit();
  EXPECT_EQ(slurp(t / "empty/a.txt"), "a");
}

TEST(OutputFolder, EarlierOutputNeedsForceAndThenIsReplacedWhole) {
  TempDir t;
  {
    OutputFolder out(t / "o", {"simulate broccoli", false, {}});
    write_text(out.path() / "old.txt", "old");
    out.commit();
  }
  const std::string e = error_message([&] { OutputFolder out(t / "o", {"simulate broccoli", false, {}}); });
  EXPECT_NE(e.find("--force replaces it"), std::string::npos) << e;
  EXPECT_NE(e.find("simulate broccoli"), std::string::npos) << e;
  OutputFolder out(t / "o", {"simulate broccoli", true, {}});
  write_text(out.path() / "new.txt", "new");
  out.commit();
  EXPECT_FALSE(fs::exists(t / "o/old.txt"));
  EXPECT_EQ(slurp(t / "o/new.txt"), "new");
  EXPECT_EQ(entries(t.path()), 1u);
}

TEST(OutputFolder, ForceRefusesAnOutputFolderTheUserAddedAFileTo) {
  TempDir t;
  {
    OutputFolder out(t / "o", {"x", false, {}});
    write_text(out.path() / "a.txt", "a");
    out.commit();
  }
  write_text(t / "o/sub/notes.md", "mine");
  const std::string e = error_message([&] { OutputFolder out(t / "o", {"x", true, {}}); });
  EXPECT_NE(e.find("sub"), std::string::npos) << e;
  EXPECT_EQ(slurp(t / "o/sub/notes.md"), "mine");
}

TEST(OutputFolder, AForgedOrDamagedMarkerIsNoMarker) {
  TempDir t;
  write_text(t / "o/.cropsight-output", "hello\n");
  write_text(t / "o/data.csv", "1,2");
  EXPECT_NE(error_message([&] { OutputFolder out(t / "o", {"x", true, {}}); }), "");
  EXPECT_TRUE(fs::exists(t / "o/data.csv"));
}

TEST(OutputRule, InputsAreNeverOutputs) {
  TempDir t;
  write_text(t / "in/seq/depth/000000.png", "x");
  const OutputPolicy p{"x", true, {t / "in/seq"}};
  // equal, inside, containing; with a trailing separator, a "..", and through a link
  fs::create_directory_symlink(t / "in", t / "link");
  for (const fs::path& out :
       std::vector<fs::path>{t / "in/seq", t / "in/seq/", t / "in/seq/out", t / "in/seq/depth/x.png", t / "in",
                             t / "in/x/../seq", t / "link/seq", t.path()}) {
    EXPECT_NE(error_message([&] { cropsight::io::check_output_folder(out, p); }), "") << out;
    EXPECT_NE(error_message([&] { cropsight::io::check_output_file(out, p); }), "") << out;
  }
  EXPECT_EQ(error_message([&] { cropsight::io::check_output_folder(t / "in/seq2", p); }), "");
  EXPECT_EQ(error_message([&] { cropsight::io::check_output_file(t / "in/seq.jsonl", p); }), "");
}

TEST(OutputRule, ExistingFileNeedsForceAndAFolderIsNoFile) {
  TempDir t;
  write_text(t / "d.jsonl", "mine");
  EXPECT_NE(error_message([&] {
              cropsight::io::check_output_file(t / "d.jsonl", {"x", false, {}});
            }).find("--force"),
            std::string::npos);
  EXPECT_EQ(error_message([&] { cropsight::io::check_output_file(t / "d.jsonl", {"x", true, {}}); }), "");
  fs::create_directory(t / "dir");
  EXPECT_NE(error_message([&] { cropsight::io::check_output_file(t / "dir", {"x", true, {}}); }), "");
  EXPECT_NE(error_message([&] { cropsight::io::check_output_folder(t / "d.jsonl", {"x", true, {}}); }), "");
  EXPECT_EQ(slurp(t / "d.jsonl"), "mine");
}

TEST(OutputRule, UnwritableLocationsAreRefusedBeforeAnyWork) {
  TempDir t;
  // /proc accepts no new files, even from root (whom access() would let through)
  EXPECT_NE(error_message([] {
              cropsight::io::check_output_file("/proc/cropsight-x/det.jsonl", {"x", false, {}});
            }),
            "");
  EXPECT_NE(error_message([] { cropsight::io::check_output_folder("/proc/cropsight-x", {"x", false, {}}); }), "");
  write_text(t / "file", "x");
  EXPECT_NE(error_message([&] { cropsight::io::check_output_file(t / "file/d.jsonl", {"x", false, {}}); }), "");
  EXPECT_EQ(entries(t.path()), 1u);  // the probes left nothing
}

}  // namespace output_test
