// `segment grape` over many clouds in one process: a folder or a list, text, PLY and PCD inputs,
// labelled outputs, the model loaded once; and its bad inputs (one line, exit 2, nothing left).
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "cropsight/io/cloud_io.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/grape_text.hpp"
#include "one_line_error.hpp"
#include "pipeline/grape/grape_test_clouds.hpp"
#include "testing/testing.hpp"

namespace segment_grape_batch_test {
using namespace cropsight;
namespace fs = std::filesystem;

// A blob cloud in metres (a bunch 0.8 m in front of the camera), colours, no normals: what
// `detect grape` and `roi-cloud` users hold.
Cloud metric_blobs(std::uint32_t seed) {
  Cloud c = cropsight::testing::two_blobs(seed, 300);
  for (auto& p : c.points) p = 0.05f * p + Eigen::Vector3f(0.01f, -0.02f, 0.8f);
  c.normals.clear();
  c.labels.clear();
  return c;
}

using cropsight::testing::expect_one_line_error;

std::string model_path() { return (cropsight::testing::source_dir() / "models" / "grape-gbdt-fast.json").string(); }

TEST(SegmentGrapeBatch, AFolderIsLabelledAsEachCloudAloneWithOneModelLoad) {
  if (!fs::exists(cropsight::testing::cli_path())) GTEST_SKIP() << "CLI not built";
  cropsight::testing::TempDir t;
  fs::create_directories(t / "in");
  for (int i = 0; i < 3; ++i)
    io::write_grape_text(t / "in" / ("c" + std::to_string(i) + ".txt"), cropsight::testing::two_blobs(10 + i, 300));
  const std::string seg = "segment grape --model '" + model_path() + "' --threads 1 ";
  auto r = cropsight::testing::run_cli(seg + "--clouds '" + (t / "in").string() + "' --out '" + (t / "out").string() +
                                       "' --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["clouds"].size(), 3u);
  EXPECT_TRUE(j.contains("startup_ms") && j.contains("mean_ms"));
  for (int i = 0; i < 3; ++i) {
    const std::string name = "c" + std::to_string(i) + ".txt";
    r = cropsight::testing::run_cli(seg + "--clouds '" + (t / "in" / name).string() + "' --out '" +
                                    (t / ("alone-" + name)).string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(io::read_grape_text(t / "out" / name).labels, io::read_grape_text(t / ("alone-" + name)).labels) << name;
    EXPECT_EQ(j["clouds"][i]["points"], 300);
  }
}

TEST(SegmentGrapeBatch, PlyAndPcdInMetresComeBackLabelledInTheirOwnCoordinates) {
  if (!fs::exists(cropsight::testing::cli_path())) GTEST_SKIP() << "CLI not built";
  cropsight::testing::TempDir t;
  const Cloud metric = metric_blobs(5);
  io::write_cloud(t / "bunch.ply", metric);
  io::write_cloud(t / "bunch.pcd", metric);
  const std::string seg = "segment grape --model '" + model_path() + "' --threads 1 --clouds ";
  auto r = cropsight::testing::run_cli(seg + "'" + (t / "bunch.ply").string() + "' --out '" +
                                       (t / "labelled.ply").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Cloud ply = io::read_cloud(t / "labelled.ply");
  ASSERT_EQ(ply.size(), metric.size());
  ASSERT_EQ(ply.labels.size(), metric.size());
  for (std::size_t i = 0; i < ply.size(); ++i) ASSERT_EQ(ply.points[i], metric.points[i]) << i;
  // The same cloud as PCD, in a list with the PLY: the same labels, whatever the file format.
  fs::create_directories(t / "pcd");
  fs::rename(t / "bunch.pcd", t / "pcd" / "other.pcd");
  r = cropsight::testing::run_cli(seg + "'" + (t / "bunch.ply").string() + "," + (t / "pcd").string() + "' --out '" +
                                  (t / "both").string() + "' --format pcd");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(io::read_cloud(t / "both" / "bunch.pcd").labels, ply.labels);
  EXPECT_EQ(io::read_cloud(t / "both" / "other.pcd").labels, ply.labels);
}

TEST(SegmentGrapeBatch, BadInputsAreOneLineAndLeaveNothing) {
  if (!fs::exists(cropsight::testing::cli_path())) GTEST_SKIP() << "CLI not built";
  cropsight::testing::TempDir t;
  fs::create_directories(t / "in");
  io::write_grape_text(t / "in" / "a.txt", cropsight::testing::two_blobs(1, 300));
  // A PLY with no vertices, after a good cloud: the folder is not left half written.
  io::write_file_atomic(t / "in" / "b.ply",
                        "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
                        "property float z\nend_header\n");
  const std::string seg = "segment grape --model '" + model_path() + "' --threads 1 --quiet --clouds ";
  auto r = cropsight::testing::run_cli(seg + "'" + (t / "in").string() + "' --out '" + (t / "out").string() + "'");
  expect_one_line_error(r, "b.ply");
  EXPECT_FALSE(fs::exists(t / "out"));
  // Two clouds that would write one file; --format with a single cloud; an unknown --out format.
  io::write_cloud(t / "in2" / "a.ply", metric_blobs(2));
  r = cropsight::testing::run_cli(seg + "'" + (t / "in" / "a.txt").string() + "," + (t / "in2").string() + "' --out '" +
                                  (t / "out").string() + "'");
  expect_one_line_error(r, "a.ply");
  r = cropsight::testing::run_cli(seg + "'" + (t / "in" / "a.txt").string() + "' --format ply --out '" +
                                  (t / "x.ply").string() + "'");
  expect_one_line_error(r, "--format");
  r = cropsight::testing::run_cli(seg + "'" + (t / "in" / "a.txt").string() + "' --out '" + (t / "x.xyz").string() +
                                  "'");
  expect_one_line_error(r, "x.xyz");
  EXPECT_FALSE(fs::exists(t / "out"));
  EXPECT_FALSE(fs::exists(t / "x.ply"));
}

}  // namespace segment_grape_batch_test
