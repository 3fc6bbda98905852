// Labelled PLY and PCD clouds train and evaluate the grape segmenter: what `segment grape` writes,
// corrected in a point-cloud editor that keeps the integer `label` field, is training data.
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "cropsight/io/cloud_io.hpp"
#include "cropsight/io/grape_text.hpp"
#include "pipeline/grape/grape_test_clouds.hpp"
#include "testing/testing.hpp"

namespace grape_labelled_clouds_test {
using namespace cropsight;
namespace fs = std::filesystem;
using cropsight::testing::run_cli;
using cropsight::testing::shell_quoted;

// A labelled blob cloud in metres (0.8 m in front of the camera), colours, no normals.
Cloud labelled_metric_blobs(std::uint32_t seed) {
  Cloud c = cropsight::testing::two_blobs(seed, 300);
  for (auto& p : c.points) p = 0.05f * p + Eigen::Vector3f(0.01f, -0.02f, 0.8f);
  c.normals.clear();
  return c;
}

TEST(GrapeLabelledClouds, PlyAndPcdTrainAndEvaluateLikeEachOther) {
  cropsight::testing::TempDir t;
  fs::create_directories(t / "ply");
  fs::create_directories(t / "pcd");
  for (std::uint32_t s = 1; s <= 3; ++s) {
    const Cloud c = labelled_metric_blobs(s);
    ASSERT_EQ(c.labels.size(), c.size());
    io::write_cloud(t / "ply" / ("c" + std::to_string(s) + ".ply"), c);
    io::write_cloud(t / "pcd" / ("c" + std::to_string(s) + ".pcd"), c);
  }
  const std::string fast = " --model gbdt --set gbdt.rounds=2 --set points_per_cloud=100 --set gbdt.nthread=1 --json";
  auto r = run_cli("train grape --clouds " + shell_quoted(t / "ply") + fast + " --out " + shell_quoted(t / "m.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["clouds"], 3);
  const std::string eval = "eval grape --threads 1 --json --model " + shell_quoted(t / "m.json") + " --clouds ";
  const auto a = run_cli(eval + shell_quoted(t / "ply"));
  const auto b = run_cli(eval + shell_quoted(t / "pcd"));
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const auto ja = nlohmann::json::parse(a.out), jb = nlohmann::json::parse(b.out);
  EXPECT_EQ(ja["points"], 900);
  EXPECT_EQ(ja["miou"], jb["miou"]);  // the same clouds, the same labels, whatever the format
  EXPECT_EQ(ja["oacc"], jb["oacc"]);

  // A cloud without labels (what a sensor writes) is not training data: one line naming it.
  Cloud bare = labelled_metric_blobs(4);
  bare.labels.clear();
  io::write_cloud(t / "ply" / "c4.ply", bare);
  r = run_cli("train grape --clouds " + shell_quoted(t / "ply") + fast + " --out " + shell_quoted(t / "m2.json"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("c4.ply"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("label"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(t / "m2.json"));
}

}  // namespace grape_labelled_clouds_test
