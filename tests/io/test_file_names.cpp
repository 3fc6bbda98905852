// What a file's name says (io/file_names.hpp).
#include "cropsight/io/file_names.hpp"

#include <gtest/gtest.h>

#include "testing/testing.hpp"

namespace file_names_test {
namespace fs = std::filesystem;
using cropsight::testing::error_message;

TEST(FileNames, LowerExtension) {
  EXPECT_EQ(cropsight::io::lower_extension("a/B.PNG"), ".png");
  EXPECT_EQ(cropsight::io::lower_extension("x.tar.GZ"), ".gz");
  EXPECT_EQ(cropsight::io::lower_extension("noext"), "");
}

TEST(FileNames, ListImagesOfAFolderOrOneFile) {
  cropsight::testing::TempDir t;
  for (const char* name : {"b.JPG", "a.png", "c.jpeg", "notes.txt"}) cropsight::testing::write_text(t / name, "x");
  fs::create_directory(t / "sub.png");  // a folder named like an image is none
  const auto images = cropsight::io::list_images(t.path());
  ASSERT_EQ(images.size(), 3u);
  EXPECT_EQ(images[0].filename(), "a.png");
  EXPECT_EQ(images[2].filename(), "c.jpeg");
  EXPECT_EQ(cropsight::io::list_images(t / "a.png"), std::vector<fs::path>{t / "a.png"});
  EXPECT_NE(error_message([&] { cropsight::io::list_images(t / "notes.txt"); }).find("notes.txt"), std::string::npos);
  fs::create_directory(t / "empty");
  EXPECT_NE(error_message([&] { cropsight::io::list_images(t / "empty"); }).find("holds no"), std::string::npos);
}

}  // namespace file_names_test
