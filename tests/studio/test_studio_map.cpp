// The field map from the page: the job over HTTP draws the heads `detect broccoli --track --map`
// maps (same model, same pass), each with the frames that detected it; a pass without poses.csv
// still maps (the filter estimates the motion) and says so; a job can be cancelled; a frame that
// cannot be read fails it with the file's name.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cropsight/tracking/field_map_io.hpp"
#include "studio_fixture.hpp"

namespace cropsight::studio_testing {

namespace fs = std::filesystem;

namespace {

nlohmann::json wait_for_map(httplib::Client& client) { return wait_for_job(client, "/api/map"); }

// The CLI's map of `seq` with the default model.
std::vector<tracking::TrackedHead> cli_map(const fs::path& seq, const fs::path& dir) {
  const auto r = testing::run_cli("detect broccoli --quiet --track --data " + testing::shell_quoted(seq) + " --out " +
                                  testing::shell_quoted(dir / "detections.jsonl") + " --map " +
                                  testing::shell_quoted(dir / "map.csv"));
  if (r.exit_code != 0) throw std::runtime_error("detect broccoli failed: " + r.err);
  return tracking::read_field_map(dir / "map.csv");
}

}  // namespace

TEST(StudioMap, DrawsTheHeadsTheCliMaps) {
  testing::TempDir dir;
  const fs::path seq = unlabelled_copy(dir.path());
  const auto expected = cli_map(seq, dir.path());
  ASSERT_FALSE(expected.empty()) << "the simulated pass should map heads";
  RunningStudio studio({.sequence = seq});
  auto client = studio.client();
  EXPECT_EQ(nlohmann::json::parse(client.Get("/api/map")->body)["state"], "idle");
  EXPECT_EQ(client.Post("/api/map", "[1]", "application/json")->status, 400);  // not a JSON object
  ASSERT_EQ(client.Post("/api/map", "{}", "application/json")->status, 202);
  const auto map = wait_for_map(client);
  ASSERT_EQ(map["state"], "done") << map;
  EXPECT_TRUE(map["poses"].get<bool>());
  ASSERT_EQ(map["heads"].size(), expected.size()) << map;
  EXPECT_EQ(map["camera"].size(), 4u);
  for (std::size_t k = 0; k < expected.size(); ++k) {
    const auto& h = map["heads"][k];
    EXPECT_EQ(h["id"], expected[k].id);
    EXPECT_NEAR(h["x"].get<double>(), expected[k].position.x(), 6e-5);  // the CSV has 4 decimals
    EXPECT_NEAR(h["y"].get<double>(), expected[k].position.y(), 6e-5);
    EXPECT_NEAR(h["diameter_mm"].get<double>(), expected[k].diameter_mm, 0.06);  // 1 decimal
    // Every head was detected on frames inside its track's span, at least once.
    const auto frames = h["frames"].get<std::vector<int>>();
    ASSERT_FALSE(frames.empty()) << h;
    EXPECT_GE(frames.front(), h["first_frame"].get<int>()) << h;
    EXPECT_LE(frames.back(), h["last_frame"].get<int>()) << h;
  }
  // Built again on request: the same map.
  ASSERT_EQ(client.Post("/api/map", "{}", "application/json")->status, 202);
  EXPECT_EQ(wait_for_map(client)["heads"], map["heads"]);
}

TEST(StudioMap, APassWithoutPosesMapsAndSaysSo) {
  testing::TempDir dir;
  const fs::path seq = unlabelled_copy(dir.path());
  fs::remove(seq / "poses.csv");
  const auto expected = cli_map(seq, dir.path());
  RunningStudio studio({.sequence = seq, .read_only = true});
  auto client = studio.client();
  ASSERT_EQ(client.Post("/api/map", "{}", "application/json")->status, 202);
  const auto map = wait_for_map(client);
  ASSERT_EQ(map["state"], "done") << map;
  EXPECT_FALSE(map["poses"].get<bool>());
  EXPECT_EQ(map["heads"].size(), expected.size());
}

TEST(StudioMap, CancelStopsAJob) {
  testing::TempDir dir;
  const fs::path seq = unlabelled_copy(dir.path());
  RunningStudio studio({.sequence = seq, .read_only = true});
  auto client = studio.client();
  ASSERT_EQ(client.Post("/api/map", "{}", "application/json")->status, 202);
  EXPECT_EQ(client.Post("/api/map/cancel", "{}", "application/json")->status, 200);
  const auto map = wait_for_map(client);
  // A pass this short may be mapped before the cancel arrives; either way the job has ended.
  EXPECT_TRUE(map["state"] == "cancelled" || map["state"] == "done") << map;
}

TEST(StudioMap, AFrameThatCannotBeReadFailsWithItsName) {
  testing::TempDir dir;
  const fs::path seq = unlabelled_copy(dir.path());
  RunningStudio studio({.sequence = seq, .read_only = true});
  // Broken after the studio checked the sequence (a disk error, a copy still running).
  testing::write_text(seq / "depth" / "000002.png", "not a PNG");
  auto client = studio.client();
  ASSERT_EQ(client.Post("/api/map", "{}", "application/json")->status, 202);
  const auto map = wait_for_map(client);
  EXPECT_EQ(map["state"], "failed") << map;
  EXPECT_NE(map["message"].get<std::string>().find("000002.png"), std::string::npos) << map;
  EXPECT_TRUE(map["heads"].empty());
}

}  // namespace cropsight::studio_testing
