// A partly labelled sequence: labelled.csv lists the frames labels/ holds (what the studio writes
// while a user labels frame by frame); the other frames read without labels.
#include <gtest/gtest.h>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/sequence.hpp"
#include "io/sequence_fixture.hpp"
#include "testing/testing.hpp"

namespace cropsight::io {
namespace {

namespace fs = std::filesystem;

class PartialLabels : public ::testing::Test {
 protected:
  void SetUp() override {
    testing::write_fixture_sequence(seq, 4);
    fs::remove(seq / "labels" / "000000.png");
    fs::remove(seq / "labels" / "000002.png");
  }
  std::string error() {
    return testing::error_message([&] { SequenceReader r(seq); });
  }
  testing::TempDir tmp;
  fs::path seq = tmp / "seq";
};

TEST_F(PartialLabels, ListedFramesAreLabelledOthersAreNot) {
  write_file_atomic(seq / "labelled.csv", "frame\n1\n3\n");
  const SequenceReader r(seq);
  EXPECT_TRUE(r.info().has_labels);
  EXPECT_EQ(r.info().labelled_frames, (std::vector<int>{1, 3}));
  EXPECT_TRUE(r.read(0).labels.empty());
  EXPECT_FALSE(r.read(1).labels.empty());
  EXPECT_TRUE(r.read(2).labels.empty());
  EXPECT_TRUE(r.info().ignored.empty());  // labelled.csv is part of the format
}

TEST_F(PartialLabels, WithoutTheListAMissingLabelFrameIsStillAnError) {
  EXPECT_NE(error().find("missing frame"), std::string::npos) << error();
}

TEST_F(PartialLabels, TheListMustMatchLabels) {
  write_file_atomic(seq / "labelled.csv", "frame\n1\n2\n3\n");
  EXPECT_NE(error().find("holds other frames than labelled.csv lists"), std::string::npos) << error();
  write_file_atomic(seq / "labelled.csv", "frame\n3\n1\n");
  EXPECT_NE(error().find("increasing order"), std::string::npos) << error();
  write_file_atomic(seq / "labelled.csv", "frame\n1\n9\n");
  EXPECT_NE(error().find("0..3"), std::string::npos) << error();
  write_file_atomic(seq / "labelled.csv", "frames\n1\n3\n");
  EXPECT_NE(error().find("header 'frame'"), std::string::npos) << error();
  write_file_atomic(seq / "labelled.csv", "frame\n1\n-3\n");
  EXPECT_NE(error().find("got '-3'"), std::string::npos) << error();
  fs::remove_all(seq / "labels");
  EXPECT_NE(error().find("no labels/"), std::string::npos) << error();
}

}  // namespace
}  // namespace cropsight::io
