// CLI tests of the sizing / tracking options: detect --track --map, eval --track (map, size and
// AP figures), report --model, and their error paths. A small simulated uk sequence and a model
// trained on it are made once for the suite (the figures are not checked against targets here:
// training and testing on one short sequence says nothing about accuracy; docs/ has the real runs).
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "chromium_check.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/sim/broccoli/broccoli_sim.hpp"
#include "cropsight/tracking/field_map_io.hpp"
#include "testing/testing.hpp"

namespace fs = std::filesystem;
using namespace cropsight;
using cropsight::testing::run_cli;
using cropsight::testing::shell_quoted;

namespace {
class TrackingCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    tmp_ = new cropsight::testing::TempDir;
    sim::BroccoliSimulator s(sim::BroccoliSimConfig{}, 21, 14);
    io::SequenceWriter w(seq(), s.camera());
    for (int i = 0; i < s.frames(); ++i) w.write(s.render(i));
    w.set_groundtruth(s.groundtruth());
    w.finish();
    const auto r = run_cli("train broccoli --data " + shell_quoted(seq()) + " --config " +
                           shell_quoted(cropsight::testing::source_dir() / "configs" / "broccoli-oes-uk.yaml") +
                           " --out " + shell_quoted(model()) + " --quiet");
    trained_ = r.exit_code == 0;
    if (!trained_) train_error_ = r.err;
  }
  static void TearDownTestSuite() {
    delete tmp_;
    tmp_ = nullptr;
  }
  void SetUp() override { ASSERT_TRUE(trained_) << "train broccoli failed: " << train_error_; }
  static fs::path seq() { return *tmp_ / "seq"; }
  static fs::path model() { return *tmp_ / "oes.json"; }
  static fs::path dir() { return tmp_->path(); }
  static cropsight::testing::TempDir* tmp_;
  static bool trained_;
  static std::string train_error_;
};
cropsight::testing::TempDir* TrackingCli::tmp_ = nullptr;
bool TrackingCli::trained_ = false;
std::string TrackingCli::train_error_;
}  // namespace

TEST_F(TrackingCli, DetectWritesTheMap) {
  const fs::path out = dir() / "det.jsonl", map = dir() / "map.csv";
  const auto r =
      run_cli("detect broccoli --data " + shell_quoted(seq()) + " --model " + shell_quoted(model()) + " --out " +
              shell_quoted(out) + " --track --map " + shell_quoted(map) + " --json --set tracking.use_poses=true");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto summary = nlohmann::json::parse(r.out);
  const auto heads = tracking::read_field_map(map);
  EXPECT_EQ(summary["map_heads"].get<std::size_t>(), heads.size());
  const int last = 14 - 1;  // the simulated sequence's last frame
  int unsized = 0;
  for (const auto& h : heads) {
    // min_track_score = 3; edge_track_score = 2 for heads seen in the first or last frame
    EXPECT_GE(h.frames_seen, h.first_frame == 0 || h.last_frame == last ? 2 : 3) << h.id;
    if (h.bbox_mm == 0.0) {  // placed by views cut by the image border only: not sized
      ++unsized;
      continue;
    }
    EXPECT_GT(h.bbox_mm, 30.0) << h.id;
    EXPECT_LT(h.bbox_mm, 300.0) << h.id;
  }
  EXPECT_LE(unsized, 1);
  const std::string lines = io::read_file(out);
  const auto first = nlohmann::json::parse(lines.substr(0, lines.find('\n')));
  ASSERT_TRUE(first.contains("heads"));
  ASSERT_TRUE(first.contains("camera_estimate"));
  EXPECT_EQ(first["heads"].size(), first["detections"].size());
  // tracking.predict_missed: every line lists the heads of T it missed (maybe none), each with the
  // id of a head the pass tracked and at least predict_min_points (10) points.
  std::size_t pos = 0, lines_seen = 0;
  while (pos < lines.size()) {
    const std::size_t end = lines.find('\n', pos);
    const auto line = nlohmann::json::parse(lines.substr(pos, end - pos));
    ASSERT_TRUE(line.contains("predicted")) << line.dump();
    for (const auto& p : line["predicted"]) {
      EXPECT_GT(p["track_id"].get<int>(), 0);
      EXPECT_GE(p["points"].get<int>(), 10);
      EXPECT_EQ(p["centroid"].size(), 3u);
    }
    ++lines_seen;
    pos = end == std::string::npos ? lines.size() : end + 1;
  }
  EXPECT_EQ(lines_seen, 14u);
}

TEST_F(TrackingCli, EvalReportsMapSizeAndTemporalAp) {
  const auto r = run_cli("eval broccoli --data " + shell_quoted(seq()) + " --model " + shell_quoted(model()) +
                         " --track --fit-size-bias --json --set tracking.use_poses=true");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* k : {"map_precision", "map_recall", "duplicate_rate", "ap50_single_frame", "ap50_temporal"}) {
    ASSERT_TRUE(j.contains(k)) << k;
    ASSERT_TRUE(j[k].is_number()) << k << " = " << j[k];
    EXPECT_GE(j[k].get<double>(), 0.0) << k;
    EXPECT_LE(j[k].get<double>(), 1.0) << k;
  }
  for (const char* k : {"count_error", "size_mede_mm", "size_mad_mm", "size_pearson_r", "size_frame_mede_mm",
                        "size_frame_mad_mm", "size_frame_pearson_r", "tracking_ms_per_frame"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_DOUBLE_EQ(j["ap50_single_frame"].get<double>(), j["ap50"].get<double>());  // same AP, two routes
  // Placement: the mean field-plane distance of matched map heads, in metres, within the 5 cm match radius.
  ASSERT_GT(j["map_matched"].get<int>(), 0);
  ASSERT_TRUE(j["map_mean_distance_m"].is_number()) << j["map_mean_distance_m"];
  EXPECT_GT(j["map_mean_distance_m"].get<double>(), 0.0);
  EXPECT_LE(j["map_mean_distance_m"].get<double>(), 0.05);
  ASSERT_TRUE(j.contains("size_bias_fit"));
  EXPECT_GT(j["size_bias_fit"]["bbox"]["scale"].get<double>(), 0.0);
}

TEST_F(TrackingCli, ReportWithModel) {
  const fs::path html = dir() / "report.html";
  const auto r = run_cli("report --data " + shell_quoted(seq()) + " --model " + shell_quoted(model()) +
                         " --frames 2 --out " + shell_quoted(html) + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string page = io::read_file(html);
  EXPECT_GE(std::size_t(std::count(page.begin(), page.end(), '<')), 100u);
  EXPECT_NE(page.find("Field map"), std::string::npos);
  EXPECT_NE(page.find("Precision"), std::string::npos);
  EXPECT_NE(page.find("data:image/png;base64"), std::string::npos);  // overlays embedded
}

TEST_F(TrackingCli, BadInputIsOneLineAndNoOutput) {
  const fs::path out = dir() / "none.jsonl", map = dir() / "none.csv", html = dir() / "none.html";
  auto r = run_cli("detect broccoli --data " + shell_quoted(seq()) + " --model " + shell_quoted(model()) + " --out " +
                   shell_quoted(out) + " --map " + shell_quoted(map));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--map"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(map));
  r = run_cli("eval broccoli --data " + shell_quoted(seq()) + " --model " + shell_quoted(model()) + " --fit-size-bias");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--track"), std::string::npos) << r.err;
  r = run_cli("eval broccoli --data " + shell_quoted(seq()) + " --model " + shell_quoted(model()) +
              " --track --set tracking.association_radius_m=0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("association_radius_m"), std::string::npos) << r.err;
  r = run_cli("eval broccoli --data " + shell_quoted(seq()) + " --model " + shell_quoted(model()) +
              " --track --set sizing.estimator=cube");
  EXPECT_EQ(r.exit_code, 2);
  r = run_cli("detect broccoli --data " + shell_quoted(seq()) + " --model " + shell_quoted(model()) + " --out " +
              shell_quoted(out) + " --track --set tracking.bogus=1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_FALSE(fs::exists(out));
  r = run_cli("report --data " + shell_quoted(seq()) + " --model " + shell_quoted(dir() / "missing.json") + " --out " +
              shell_quoted(html));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_FALSE(fs::exists(html));
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

// A user's own recording has no labels: the report shows what the pipeline found (the same map as
// `detect --track --map` on it) and no metric.
TEST_F(TrackingCli, ReportOnASequenceWithoutGroundTruth) {
  const fs::path own = dir() / "own";
  fs::copy(seq(), own, fs::copy_options::recursive);
  fs::remove_all(own / "labels");
  fs::remove(own / "groundtruth.json");
  const fs::path html = dir() / "own.html", map = dir() / "own-map.csv";
  auto r = run_cli("report --data " + shell_quoted(own) + " --model " + shell_quoted(model()) + " --frames 2 --out " +
                   shell_quoted(html) + " --json --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out)["broccoli"];
  EXPECT_EQ(j["ground_truth"], false);
  r = run_cli("detect broccoli --data " + shell_quoted(own) + " --model " + shell_quoted(model()) + " --out " +
              shell_quoted(dir() / "own.jsonl") + " --track --map " + shell_quoted(map) + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto heads = tracking::read_field_map(map);
  ASSERT_GT(heads.size(), 0u);
  EXPECT_EQ(j["map_heads"], std::to_string(heads.size()));
  const std::string page = io::read_file(html);
  EXPECT_NE(page.find("no ground truth"), std::string::npos);
  EXPECT_NE(page.find("detections per frame"), std::string::npos);
  EXPECT_NE(page.find("mapped heads per diameter"), std::string::npos);
  EXPECT_EQ(page.find("Precision–recall"), std::string::npos);  // no metric without truth
  EXPECT_NE(page.find("data:image/png;base64"), std::string::npos);
  // Opened in Chromium: the overlays decode and every chart is laid out.
  const std::string chromium = cropsight::testing::chromium_path();
  if (chromium.empty()) GTEST_SKIP() << "chromium not installed (command -v chromium): the page was not opened";
  fs::create_directories(dir() / "own-render");
  const auto shown = cropsight::testing::render_check(chromium, html, dir() / "own-render");
  ASSERT_TRUE(shown.is_object()) << "chromium gave no render check";
  EXPECT_EQ(shown["bad"], nlohmann::json::array()) << shown.dump();
  EXPECT_GE(shown["imgs"].get<int>(), 2) << shown.dump();  // the two overlay frames
  EXPECT_GE(shown["svgs"].get<int>(), 4) << shown.dump();  // detections, map, sizes, timing
}

// The size correction is fitted on the training passes and travels in the model: the values
// recorded equal what `eval --track --fit-size-bias` fits on the same passes with the same model,
// and a command that loads the model sizes with them.
TEST_F(TrackingCli, TrainRecordsTheSizeCorrectionInTheModel) {
  const fs::path fitted = dir() / "fitted.json";
  auto r = run_cli("train broccoli --data " + shell_quoted(seq()) + " --config " +
                   shell_quoted(cropsight::testing::source_dir() / "configs" / "broccoli-oes-uk.yaml") +
                   " --fit-size-bias --out " + shell_quoted(fitted) + " --quiet --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto trained = nlohmann::json::parse(r.out)["size_correction"];
  const auto config = nlohmann::json::parse(io::read_file(fitted))["config"];
  EXPECT_EQ(std::stod(config["sizing.hull_scale"].get<std::string>()), trained["sizing.hull_scale"].get<double>());
  EXPECT_EQ(config["sizing.hull_max_points"], "500");
  r = run_cli("eval broccoli --data " + shell_quoted(seq()) + " --model " + shell_quoted(model()) +
              " --track --fit-size-bias --json --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto fit = nlohmann::json::parse(r.out)["size_bias_fit"];
  EXPECT_NEAR(trained["sizing.hull_scale"].get<double>(), fit["hull"]["scale"].get<double>(), 1e-9);
  EXPECT_NEAR(trained["sizing.hull_offset_mm"].get<double>(), fit["hull"]["offset_mm"].get<double>(), 1e-9);
  EXPECT_NEAR(trained["sizing.bbox_scale"].get<double>(), fit["bbox"]["scale"].get<double>(), 1e-9);
  // Sizes with the recorded correction differ from the uncorrected model's (scale ≠ 1 or offset ≠ 0).
  r = run_cli("eval broccoli --data " + shell_quoted(seq()) + " --model " + shell_quoted(fitted) +
              " --track --json --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto corrected = nlohmann::json::parse(r.out);
  r = run_cli("eval broccoli --data " + shell_quoted(seq()) + " --model " + shell_quoted(model()) +
              " --track --json --quiet");
  const auto raw = nlohmann::json::parse(r.out);
  EXPECT_EQ(corrected["size_estimator"], "hull");
  EXPECT_NE(corrected["size_mede_mm"], raw["size_mede_mm"]);
}

// --overlay: one viewable picture per frame, written whole; it may not be the --masks folder.
TEST_F(TrackingCli, DetectWritesAnOverlayPerFrame) {
  const fs::path overlay = dir() / "overlay", masks = dir() / "masks-o";
  auto r = run_cli("detect broccoli --data " + shell_quoted(seq()) + " --model " + shell_quoted(model()) + " --out " +
                   shell_quoted(dir() / "o.jsonl") + " --track --masks " + shell_quoted(masks) + " --overlay " +
                   shell_quoted(overlay) + " --quiet --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["overlay"], overlay.string());
  int pictures = 0;
  for (const auto& e : fs::directory_iterator(overlay)) pictures += e.path().extension() == ".png";
  EXPECT_EQ(pictures, io::SequenceReader(seq()).size());
  r = run_cli("detect broccoli --data " + shell_quoted(seq()) + " --model " + shell_quoted(model()) + " --out " +
              shell_quoted(dir() / "o2.jsonl") + " --masks " + shell_quoted(dir() / "same") + " --overlay " +
              shell_quoted(dir() / "same") + " --quiet");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_FALSE(fs::exists(dir() / "same"));
  EXPECT_FALSE(fs::exists(dir() / "o2.jsonl"));
}
