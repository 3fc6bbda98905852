// Sequence format: round trip, determinism, atomic writing.
#include <gtest/gtest.h>

#include "cropsight/core/error.hpp"
#include "cropsight/io/config_yaml.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/sequence.hpp"
#include "io/sequence_fixture.hpp"
#include "testing/testing.hpp"

namespace cropsight::io {
namespace {

using namespace cropsight::testing;
namespace fs = std::filesystem;

TEST(Sequence, FrameFileName) {
  EXPECT_EQ(frame_file_name(0), "000000.png");
  EXPECT_EQ(frame_file_name(42), "000042.png");
}

TEST(Sequence, CameraYamlRoundTripIsExact) {
  TempDir tmp;
  CameraIntrinsics c = fixture_camera();
  c.fx = 1.0 / 3.0;  // needs all 17 digits to round-trip
  c.distortion = {0.1, -0.02, 1e-5, 0, 0.003};
  c.sensor = "kinect \"v2\"";
  write_camera_yaml(tmp / "camera.yaml", c);
  const CameraIntrinsics r = read_camera_yaml(tmp / "camera.yaml");
  EXPECT_EQ(r.width, c.width);
  EXPECT_EQ(r.height, c.height);
  EXPECT_EQ(r.fx, c.fx);
  EXPECT_EQ(r.fy, c.fy);
  EXPECT_EQ(r.cx, c.cx);
  EXPECT_EQ(r.cy, c.cy);
  EXPECT_EQ(r.depth_scale, c.depth_scale);
  EXPECT_EQ(r.distortion, c.distortion);
  EXPECT_EQ(r.sensor, c.sensor);
}

TEST(Sequence, RoundTripEveryFile) {
  TempDir tmp;
  const fs::path dir = tmp / "seq";
  write_fixture_sequence(dir, 4);
  SequenceReader r(dir);
  EXPECT_EQ(r.size(), 4);
  EXPECT_TRUE(r.info().has_color);
  EXPECT_TRUE(r.info().has_labels);
  EXPECT_TRUE(r.info().has_poses);
  EXPECT_TRUE(r.info().has_groundtruth);
  const CameraIntrinsics cam = fixture_camera();
  EXPECT_EQ(r.info().camera.fx, cam.fx);
  for (int i = 0; i < 4; ++i) {
    const RgbdFrame want = fixture_frame(i, cam);
    const RgbdFrame got = r.read(i);
    EXPECT_EQ(got.index, i);
    EXPECT_EQ(got.depth, want.depth);
    EXPECT_EQ(got.color, want.color);
    EXPECT_EQ(got.labels, want.labels);
    EXPECT_EQ(got.timestamp, want.timestamp);
    ASSERT_TRUE(got.camera_position.has_value());
    EXPECT_EQ(*got.camera_position, *want.camera_position);
  }
  const GroundTruth want = fixture_truth();
  const GroundTruth& got = r.groundtruth();
  ASSERT_EQ(got.instances.size(), want.instances.size());
  for (std::size_t k = 0; k < want.instances.size(); ++k) {
    EXPECT_EQ(got.instances[k].id, want.instances[k].id);
    EXPECT_EQ(got.instances[k].position, want.instances[k].position);
    EXPECT_EQ(got.instances[k].diameter_mm, want.instances[k].diameter_mm);
    EXPECT_EQ(got.instances[k].extra, want.instances[k].extra);
  }
  EXPECT_EQ(got.attributes, want.attributes);
  EXPECT_EQ(r.poses().size(), 4u);
}

TEST(Sequence, DepthOnlySequence) {
  TempDir tmp;
  write_fixture_sequence(tmp / "seq", 2, false, false, false, false);
  SequenceReader r(tmp / "seq");
  EXPECT_FALSE(r.info().has_color || r.info().has_labels || r.info().has_poses || r.info().has_groundtruth);
  EXPECT_FALSE(fs::exists(tmp / "seq" / "poses.csv"));
  const RgbdFrame f = r.read(1);
  EXPECT_TRUE(f.color.empty());
  EXPECT_TRUE(f.labels.empty());
  EXPECT_FALSE(f.camera_position.has_value());
}

TEST(Sequence, WritingIsDeterministic) {
  TempDir tmp;
  write_fixture_sequence(tmp / "a", 3);
  write_fixture_sequence(tmp / "b", 3);
  std::vector<std::string> names;
  for (const auto& e : fs::recursive_directory_iterator(tmp / "a")) {
    if (!e.is_regular_file()) continue;
    const fs::path rel = fs::relative(e.path(), tmp / "a");
    names.push_back(rel.string());
    EXPECT_EQ(read_file(e.path()), read_file(tmp / "b" / rel)) << rel;
  }
  // camera + 3 dirs x 3 frames + poses + truth + the output marker (io/output.hpp)
  EXPECT_EQ(names.size(), 1u + 3u * 3u + 2u + 1u);
}

TEST(Sequence, GroundTruthJsonHasFixedKeyOrder) {
  TempDir tmp;
  write_fixture_sequence(tmp / "seq", 1);
  const std::string j = read_file(tmp / "seq" / "groundtruth.json");
  const auto id = j.find("\"id\""), pos = j.find("\"position\""), dia = j.find("\"diameter_mm\""),
             h = j.find("\"height_m\"");
  ASSERT_NE(h, std::string::npos);
  EXPECT_LT(id, pos);
  EXPECT_LT(pos, dia);
  EXPECT_LT(dia, h);
}

std::vector<std::string> entries(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
  return out;
}

TEST(Sequence, NothingVisibleUntilFinish) {
  TempDir tmp;
  const CameraIntrinsics cam = fixture_camera();
  SequenceWriter w(tmp / "seq", cam);
  w.write(fixture_frame(0, cam));
  EXPECT_FALSE(fs::exists(tmp / "seq"));
  w.finish();
  EXPECT_TRUE(fs::exists(tmp / "seq" / "depth" / "000000.png"));
  EXPECT_EQ(entries(tmp.path()), std::vector<std::string>{"seq"});  // temp dir renamed away
}

TEST(Sequence, AbandonedWriterLeavesNothing) {
  TempDir tmp;
  const CameraIntrinsics cam = fixture_camera();
  {
    SequenceWriter w(tmp / "seq", cam);
    w.write(fixture_frame(0, cam));
    w.write(fixture_frame(1, cam));
  }
  EXPECT_TRUE(entries(tmp.path()).empty());
}

// A run killed by a signal cannot unwind and leaves its hidden temporary; the next writer of the
// same sequence removes it when its process is gone, and leaves a live writer's alone.
TEST(Sequence, LeftoversOfAKilledWriterAreRemovedByTheNext) {
  TempDir tmp;
  const CameraIntrinsics cam = fixture_camera();
  // pid 999999999 is above Linux's pid_max (4194304), so no such process exists
  const fs::path dead = tmp / ".seq.tmp-999999999-42", live = tmp / (".seq.tmp-1-7"),
                 other = tmp / ".other.tmp-999999999-1";
  for (const auto& d : {dead, live, other}) fs::create_directories(d / "depth");
  SequenceWriter w(tmp / "seq", cam);
  w.write(fixture_frame(0, cam));
  w.finish();
  EXPECT_FALSE(fs::exists(dead));
  EXPECT_TRUE(fs::exists(live));   // pid 1 is alive (or not ours to judge)
  EXPECT_TRUE(fs::exists(other));  // another sequence's temporary
  EXPECT_TRUE(fs::exists(tmp / "seq" / "depth" / "000000.png"));
}

// io::TempDirectory (detect --masks, detect potato, simulate seedling ...) cleans up after killed
// runs like SequenceWriter does.
TEST(Files, TempDirectoryRemovesWhatKilledRunsLeft) {
  TempDir tmp;
  const fs::path dead = tmp / ".masks.tmp-999999999-42", dead_old = tmp / ".masks.tmp-999999999-43.old",
                 live = tmp / ".masks.tmp-1-7", other = tmp / ".other.tmp-999999999-1";
  for (const auto& d : {dead, dead_old, live, other}) fs::create_directories(d);
  write_file_atomic(dead / "000000.png", "partial");
  {
    TempDirectory t(tmp / "masks");
    EXPECT_FALSE(fs::exists(dead));
    EXPECT_FALSE(fs::exists(dead_old));
    EXPECT_TRUE(fs::exists(live));
    EXPECT_TRUE(fs::exists(other));
    write_file_atomic(t.path() / "000000.png", "new");
    t.commit("masks");
  }
  EXPECT_EQ(read_file(tmp / "masks" / "000000.png"), "new");
}

// A previous folder is swapped out in one step and removed: only the new contents remain.
TEST(Files, ReplaceDirectoryLeavesOnlyTheNewContents) {
  TempDir tmp;
  write_file_atomic(tmp / "out" / "a.txt", "old");
  write_file_atomic(tmp / "out" / "only-old.txt", "old");
  {
    TempDirectory t(tmp / "out");
    write_file_atomic(t.path() / "a.txt", "new");
    t.commit();
  }
  EXPECT_EQ(entries(tmp.path()), std::vector<std::string>{"out"});
  EXPECT_EQ(entries(tmp / "out"), std::vector<std::string>{"a.txt"});
  EXPECT_EQ(read_file(tmp / "out" / "a.txt"), "new");
}

TEST(Files, DirectoriesAreNamedAsSuch) {
  TempDir tmp;
  fs::create_directories(tmp / "d");
  try {
    write_file_atomic(tmp / "d", "x");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("is a directory"), std::string::npos) << e.what();
  }
  try {
    read_file(tmp / "d");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("is a directory"), std::string::npos) << e.what();
  }
  EXPECT_EQ(entries(tmp.path()).size(), 1u);  // no temporary left
}

TEST(Files, DuplicateConfigKeysAreAnError) {
  TempDir tmp;
  write_file_atomic(tmp / "c.yaml", "oes:\n  min_size: 300\n  max_size: 9000\n  min_size: 500\n");
  try {
    load_config_map(tmp / "c.yaml");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.where(), (tmp / "c.yaml").string());
    EXPECT_NE(std::string(e.what()).find("duplicate key 'oes.min_size'"), std::string::npos) << e.what();
  }
}

// The preset reader had camera.yaml's bug (fuzz_camera_yaml): a key that is a mapping escaped as
// YAML::TypedBadConversion.
TEST(Sequence, ConfigKeyThatIsAMappingIsAnError) {
  TempDir tmp;
  write_file_atomic(tmp / "c.yaml", "oes:\n  {a: 1}: 300\n");
  try {
    load_config_map(tmp / "c.yaml");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.where(), (tmp / "c.yaml").string());
    EXPECT_NE(std::string(e.what()).find("line 2: a key must be a plain name, not a mapping"), std::string::npos)
        << e.what();
  }
}

TEST(Sequence, FailedWriteLeavesNothing) {
  TempDir tmp;
  const CameraIntrinsics cam = fixture_camera();
  {
    SequenceWriter w(tmp / "seq", cam);
    w.write(fixture_frame(0, cam));
    RgbdFrame bad = fixture_frame(1, cam);
    bad.depth = DepthImage(5, 5);
    EXPECT_THROW(w.write(bad), Error);
    RgbdFrame out_of_order = fixture_frame(3, cam);
    EXPECT_THROW(w.write(out_of_order), Error);
    RgbdFrame no_color = fixture_frame(1, cam, false);
    EXPECT_THROW(w.write(no_color), Error);
    GroundTruth t = fixture_truth();
    t.instances[1].id = 1;  // duplicate
    w.set_groundtruth(t);
    EXPECT_THROW(w.finish(), Error);
  }
  EXPECT_TRUE(entries(tmp.path()).empty());
}

TEST(Sequence, RefusesToOverwriteUnlessAsked) {
  TempDir tmp;
  write_fixture_sequence(tmp / "seq", 2);
  const CameraIntrinsics cam = fixture_camera();
  EXPECT_THROW(SequenceWriter(tmp / "seq", cam), Error);
  {
    SequenceWriter w(tmp / "seq", cam, /*overwrite=*/true);
    w.write(fixture_frame(0, cam));
    // Not finished: the old sequence must survive untouched.
  }
  EXPECT_EQ(SequenceReader(tmp / "seq").size(), 2);
  {
    SequenceWriter w(tmp / "seq", cam, true);
    w.write(fixture_frame(0, cam));
    w.finish();
  }
  EXPECT_EQ(SequenceReader(tmp / "seq").size(), 1);
  EXPECT_EQ(entries(tmp.path()), std::vector<std::string>{"seq"});
}

TEST(Sequence, NeverReplacesANonSequenceDirectory) {
  TempDir tmp;
  write_file_atomic(tmp / "docs" / "thesis.tex", "precious");
  EXPECT_THROW(SequenceWriter(tmp / "docs", fixture_camera(), true), Error);
  EXPECT_EQ(read_file(tmp / "docs" / "thesis.tex"), "precious");
}

TEST(Sequence, FinishWithoutFramesIsAnError) {
  TempDir tmp;
  SequenceWriter w(tmp / "seq", fixture_camera());
  EXPECT_THROW(w.finish(), Error);
  EXPECT_FALSE(fs::exists(tmp / "seq"));
}

}  // namespace
}  // namespace cropsight::io
