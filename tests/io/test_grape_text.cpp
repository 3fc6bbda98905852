#include <gtest/gtest.h>

#include <fstream>

#include "cropsight/core/error.hpp"
#include "cropsight/io/grape_text.hpp"
#include "testing/testing.hpp"

namespace {
using cropsight::Error;
using cropsight::testing::TempDir;

using cropsight::testing::write_text;

std::string error_of(const std::filesystem::path& p) {
  try {
    cropsight::io::read_grape_text(p);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(GrapeText, ReadsAllChannels) {
  TempDir t;
  write_text(t / "a.txt", "0.1 0.2 0.3 0 0 1 0.5 0.25 1 2.000000\n-1 -2 -3 1 0 0 0 0 0 5.0\n\n");
  const auto c = cropsight::io::read_grape_text(t / "a.txt");
  ASSERT_EQ(c.size(), 2u);
  EXPECT_FLOAT_EQ(c.points[0].y(), 0.2f);
  EXPECT_FLOAT_EQ(c.normals[0].z(), 1.f);
  EXPECT_FLOAT_EQ(c.colors[0].y(), 0.25f);
  EXPECT_EQ(c.labels[0], 2);
  EXPECT_EQ(c.labels[1], 5);
}

TEST(GrapeText, ErrorsNameFileAndLine) {
  TempDir t;
  write_text(t / "short.txt", "0 0 0 0 0 1 0 0 0 1\n0 0 0 0 0 1 0 0 0\n");
  const std::string e1 = error_of(t / "short.txt");
  EXPECT_NE(e1.find("short.txt"), std::string::npos) << e1;
  EXPECT_NE(e1.find("line 2"), std::string::npos) << e1;
  EXPECT_NE(e1.find("got 9"), std::string::npos) << e1;

  write_text(t / "bad.txt", "0 0 0 0 0 1 0 0 0 1\n0 0 0 0 0 1 0 0 0 1\n0 0 abc 0 0 1 0 0 0 1\n");
  const std::string e2 = error_of(t / "bad.txt");
  EXPECT_NE(e2.find("bad.txt: line 3"), std::string::npos) << e2;
  EXPECT_NE(e2.find("abc"), std::string::npos) << e2;

  write_text(t / "label.txt", "0 0 0 0 0 1 0 0 0 1.5\n");
  EXPECT_NE(error_of(t / "label.txt").find("line 1: label"), std::string::npos);
  write_text(t / "empty.txt", "\n");
  EXPECT_NE(error_of(t / "empty.txt").find("no points"), std::string::npos);
  EXPECT_NE(error_of(t / "missing.txt").find("missing.txt: cannot open"), std::string::npos);
}

TEST(GrapeText, WriteReadRoundTripAndListing) {
  TempDir t;
  cropsight::Cloud c;
  c.points = {{0.125f, -0.5f, 0.25f}, {1, 2, 3}};
  c.normals = {{0, 0, 1}, {0, 1, 0}};
  c.colors = {{0.5f, 0.5f, 0.5f}, {1, 0, 0}};
  c.labels = {3, 1};
  std::filesystem::create_directories(t / "points");
  cropsight::io::write_grape_text(t / "points" / "b.txt", c);
  cropsight::io::write_grape_text(t / "points" / "a.txt", c);
  const auto files = cropsight::io::list_grape_clouds(t.path());
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(files[0].filename(), "a.txt");
  const auto r = cropsight::io::read_grape_text(files[1]);
  EXPECT_EQ(r.labels, c.labels);
  EXPECT_TRUE(r.points[0].isApprox(c.points[0]));
  EXPECT_THROW(cropsight::io::list_grape_clouds(t / "nope"), Error);
}

TEST(GrapeText, ReadsSharedCloud) {
  const auto archive = cropsight::testing::shared_data_dir() / "grape" / "grape_points_train.tar.gz";
  CROPSIGHT_REQUIRE_DATA(archive);
  // The archive is not read in place; this test only checks that the loader rejects
  // a .tar.gz with a clear message rather than parsing binary data.
  EXPECT_NE(error_of(archive).find("line 1"), std::string::npos);
}
}  // namespace
