// Labels saved through the studio train models: the page's training job over HTTP (held-out
// figures, keep without overwriting), and `train broccoli` on the same partly labelled sequence.
#include <gtest/gtest.h>

#include <chrono>
#include <nlohmann/json.hpp>
#include <thread>

#include "cropsight/io/image_io.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/learning/model.hpp"
#include "studio_fixture.hpp"

namespace cropsight::studio_testing {

namespace fs = std::filesystem;

namespace {

// The simulator's heads of `frame` as the page would post them: one run list per head id.
std::string truth_body(int frame) {
  const LabelImage labels = io::read_u16(simulated_pass() / "labels" / io::frame_file_name(frame));
  std::map<int, nlohmann::json> heads;
  for (std::size_t p = 0; p < labels.size(); ++p) {
    const int id = labels.data[p];
    if (!id) continue;
    auto& runs = heads.try_emplace(id, nlohmann::json::array()).first->second;
    if (!runs.empty() && runs[runs.size() - 2].get<std::size_t>() + runs.back().get<std::size_t>() == p)
      runs.back() = runs.back().get<int>() + 1;
    else
      runs.insert(runs.end(), {int(p), 1});
  }
  nlohmann::json list = nlohmann::json::array();
  for (auto& [id, runs] : heads) list.push_back(runs);
  return nlohmann::json{{"heads", list}}.dump();
}

nlohmann::json wait_for_training(httplib::Client& client) { return wait_for_job(client, "/api/train"); }

}  // namespace

TEST(StudioTraining, TrainsOnSavedLabelsAndKeepsWithoutOverwriting) {
  testing::TempDir dir;
  const fs::path seq = unlabelled_copy(dir.path());
  const fs::path models = dir / "models";
  fs::create_directory(models);
  testing::write_text(models / "studio-seq-1.json", "a user's file");
  studio::StudioOptions o;
  o.sequence = seq;
  o.models_dir = models;
  RunningStudio studio(o);
  auto client = studio.client();
  // Nothing to train on yet.
  ASSERT_EQ(client.Post("/api/train", "{}", "application/json")->status, 202);
  auto status = wait_for_training(client);
  EXPECT_EQ(status["state"], "failed");
  EXPECT_NE(status["message"].get<std::string>().find("two frames"), std::string::npos) << status;

  for (int f = 0; f < 4; ++f)
    ASSERT_EQ(client.Post("/api/frame/" + std::to_string(f) + "/labels", truth_body(f), "application/json")->status,
              200);
  EXPECT_EQ(client.Post("/api/train/keep", "{}", "application/json")->status, 409);  // no model yet
  ASSERT_EQ(client.Post("/api/train", "{}", "application/json")->status, 202);
  status = wait_for_training(client);
  ASSERT_EQ(status["state"], "done") << status;
  EXPECT_EQ(status["train_frames"], nlohmann::json({0, 1, 2}));
  EXPECT_EQ(status["test_frames"], nlohmann::json({3}));
  EXPECT_EQ(status["trained"]["frames"], 1);
  EXPECT_GT(status["trained"]["heads"].get<int>(), 0);
  EXPECT_TRUE(status["trained"]["kappa"].is_number()) << status;
  EXPECT_GT(status["positives"].get<int>(), 0);

  const auto kept = client.Post("/api/train/keep", "{}", "application/json");
  ASSERT_EQ(kept->status, 200) << kept->body;
  const fs::path file = nlohmann::json::parse(kept->body)["model"].get<std::string>();
  EXPECT_EQ(file, models / "studio-seq-2.json");  // -1 was the user's
  EXPECT_EQ(io::read_file(models / "studio-seq-1.json"), "a user's file");
  EXPECT_NO_THROW(learning::load_model(file));
  EXPECT_EQ(client.Post("/api/train/keep", "{}", "application/json")->status, 409);  // kept once
  for (const auto& e : fs::directory_iterator(models))                               // no temporary left
    EXPECT_EQ(e.path().filename().string().rfind("studio-seq-", 0), 0u) << e.path();

  // The CLI trains on the same labels: the four labelled frames only.
  const auto r = testing::run_cli("train broccoli --quiet --json --data " + testing::shell_quoted(seq) + " --out " +
                                  testing::shell_quoted(dir / "cli.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["frames"], 4);
}

TEST(StudioTraining, CancelStopsAJob) {
  testing::TempDir dir;
  const fs::path seq = unlabelled_copy(dir.path());
  RunningStudio studio({.sequence = seq});
  auto client = studio.client();
  for (int f = 0; f < 4; ++f)
    ASSERT_EQ(client.Post("/api/frame/" + std::to_string(f) + "/labels", truth_body(f), "application/json")->status,
              200);
  ASSERT_EQ(client.Post("/api/train", "{}", "application/json")->status, 202);
  EXPECT_EQ(client.Post("/api/train/cancel", "{}", "application/json")->status, 200);
  const auto status = wait_for_training(client);
  // A job this small may finish before the cancel arrives; either way it has ended.
  EXPECT_TRUE(status["state"] == "cancelled" || status["state"] == "done") << status;
}

// Two short simulated passes stand in for the general model's training set (--general-data).
TEST(StudioTraining, TrainsWithTheGeneralPassesWhenAsked) {
  testing::TempDir dir;
  const fs::path seq = unlabelled_copy(dir.path());
  std::vector<fs::path> general;
  for (int seed : {21, 22}) {
    general.push_back(dir / ("general-" + std::to_string(seed)));
    const auto r = testing::run_cli("simulate broccoli --frames 2 --quiet --seed " + std::to_string(seed) + " --out " +
                                    testing::shell_quoted(general.back()));
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  RunningStudio studio({.sequence = seq, .general_data = general});
  auto client = studio.client();
  const auto info = nlohmann::json::parse(client.Get("/api/info")->body);
  EXPECT_EQ(info["general_passes"], 2);
  EXPECT_EQ(info["general_frames"], 4);
  for (int f = 0; f < 4; ++f)
    ASSERT_EQ(client.Post("/api/frame/" + std::to_string(f) + "/labels", truth_body(f), "application/json")->status,
              200);
  EXPECT_EQ(client.Post("/api/train", R"({"with_general": 1})", "application/json")->status, 400);
  // Without, then with the general passes: the same held-out frame, more training samples.
  ASSERT_EQ(client.Post("/api/train", R"({"with_general": false})", "application/json")->status, 202);
  const auto alone = wait_for_training(client);
  ASSERT_EQ(alone["state"], "done") << alone;
  EXPECT_FALSE(alone["with_general"].get<bool>());
  ASSERT_EQ(client.Post("/api/train", R"({"with_general": true})", "application/json")->status, 202);
  const auto both = wait_for_training(client);
  ASSERT_EQ(both["state"], "done") << both;
  EXPECT_TRUE(both["with_general"].get<bool>());
  EXPECT_EQ(both["general_frames"], 4);
  EXPECT_EQ(both["test_frames"], alone["test_frames"]);
  EXPECT_GT(both["samples"].get<long>(), alone["samples"].get<long>());

  const auto kept = client.Post("/api/train/keep", "{}", "application/json");
  ASSERT_EQ(kept->status, 200) << kept->body;
  const auto model = learning::load_model(nlohmann::json::parse(kept->body)["model"].get<std::string>());
  EXPECT_EQ(model.info.provenance.at("extra_data"), general[0].string() + "," + general[1].string());
  EXPECT_EQ(model.info.provenance.at("frames"), "7");  // 3 of the sequence + 2 × 2 general
  EXPECT_EQ(model.info.provenance.at("data"), seq.string());
}

TEST(StudioTraining, WithoutGeneralPassesTheRequestIsRefused) {
  testing::TempDir dir;
  const fs::path seq = unlabelled_copy(dir.path());
  RunningStudio studio({.sequence = seq});
  auto client = studio.client();
  EXPECT_EQ(nlohmann::json::parse(client.Get("/api/info")->body)["general_passes"], 0);
  const auto r = client.Post("/api/train", R"({"with_general": true})", "application/json");
  EXPECT_EQ(r->status, 400);
  EXPECT_NE(r->body.find("--general-data"), std::string::npos) << r->body;
  EXPECT_EQ(nlohmann::json::parse(client.Get("/api/train")->body)["state"], "idle");
}

}  // namespace cropsight::studio_testing
