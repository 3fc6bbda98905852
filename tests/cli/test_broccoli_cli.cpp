// CLI tests of train / detect / eval / bench broccoli: success paths on a small simulated
// sequence and every error path (missing model, wrong pipeline, bad --set, missing data).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>

#include "cropsight/io/config_yaml.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/learning/model.hpp"
#include "cropsight/pipeline/broccoli/training.hpp"
#include "pipeline/broccoli/broccoli_sim_frames.hpp"
#include "testing/testing.hpp"

namespace fs = std::filesystem;
using namespace cropsight;
using cropsight::testing::run_cli;
using cropsight::testing::shell_quoted;

namespace {
class BroccoliCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    tmp_ = new cropsight::testing::TempDir;
    sim::BroccoliSimulator s(sim::BroccoliSimConfig{}, 21, 6);
    io::SequenceWriter w(seq(), s.camera());
    for (int i = 0; i < s.frames(); ++i) w.write(s.render(i));
    w.set_groundtruth(s.groundtruth());
    w.finish();
  }
  static void TearDownTestSuite() {
    delete tmp_;
    tmp_ = nullptr;
  }
  static fs::path seq() { return *tmp_ / "seq"; }
  static fs::path dir() { return tmp_->path(); }
  static cropsight::testing::TempDir* tmp_;
};
cropsight::testing::TempDir* BroccoliCli::tmp_ = nullptr;
}  // namespace

TEST_F(BroccoliCli, TrainEvalDetectAndErrors) {
  const fs::path model = dir() / "oes.json";
  auto r = run_cli("train broccoli --data " + shell_quoted(seq()) +
                   " --pipeline oes --features vfh --classifier svm-rbf --config broccoli-oes-uk --out " +
                   shell_quoted(model) + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto tj = nlohmann::json::parse(r.out);
  EXPECT_EQ(tj["frames"], 6);
  EXPECT_GT(tj["positives"].get<int>(), 0);
  const learning::Model m = learning::load_model(model);
  EXPECT_EQ(m.info.pipeline, "oes");
  EXPECT_EQ(m.info.features, std::vector<std::string>{"vfh"});
  EXPECT_NEAR(std::stod(m.info.config.at("oes.distance_tolerance")), 0.005, 1e-9);  // the preset value was recorded
  EXPECT_EQ(m.info.provenance.at("seeds"), "21");

  r = run_cli("eval broccoli --data " + shell_quoted(seq()) + " --model " + shell_quoted(model) + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto ej = nlohmann::json::parse(r.out);
  for (const char* k : {"frames", "clusters", "accuracy", "precision", "recall", "specificity", "npv", "kappa", "ap50",
                        "map50_95", "fps"})
    EXPECT_TRUE(ej.contains(k)) << k;
  EXPECT_EQ(ej["frames"], 6);
  EXPECT_GT(ej["fps"].get<double>(), 0.0);

  const fs::path out = dir() / "det.jsonl", masks = dir() / "masks";
  r = run_cli("detect broccoli --data " + shell_quoted(seq()) + " --model " + shell_quoted(model) + " --out " +
              shell_quoted(out) + " --masks " + shell_quoted(masks));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(out);
  int lines = 0;
  for (std::string line; std::getline(in, line); ++lines) {
    const auto j = nlohmann::json::parse(line);
    EXPECT_EQ(j["frame"], lines);
    for (const auto& d : j["detections"]) {
      EXPECT_EQ(d["centroid"].size(), 3u);
      EXPECT_EQ(d["box"].size(), 4u);
      EXPECT_GT(d["points"].get<int>(), 0);
    }
  }
  EXPECT_EQ(lines, 6);
  EXPECT_TRUE(fs::exists(masks / "000005.png"));

  // Errors: one line naming the problem, exit 2, no output file.
  const fs::path none = dir() / "none.jsonl";
  r = run_cli("detect broccoli --data " + shell_quoted(seq()) + " --model " + shell_quoted(dir() / "missing.json") +
              " --out " + shell_quoted(none));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("missing.json"), std::string::npos) << r.err;
  r = run_cli("detect broccoli --data " + shell_quoted(seq()) + " --model " + shell_quoted(model) + " --out " +
              shell_quoted(none) + " --set pipeline=fec");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("pipeline 'oes'"), std::string::npos) << r.err;
  r = run_cli("eval broccoli --data " + shell_quoted(seq()) + " --model " + shell_quoted(model) +
              " --set oes.no_such_key=1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no_such_key"), std::string::npos) << r.err;
  r = run_cli("eval broccoli --data " + shell_quoted(dir() / "no-seq") + " --model " + shell_quoted(model));
  EXPECT_EQ(r.exit_code, 2);
  r = run_cli("train broccoli --data " + shell_quoted(seq()) + " --pipeline watershed --out " +
              shell_quoted(dir() / "x.json"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("watershed"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(none));
  EXPECT_FALSE(fs::exists(dir() / "x.json"));
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

TEST_F(BroccoliCli, BenchReportsEveryPipelineAndThePclReference) {
  const fs::path model = dir() / "bench.json";
  auto r = run_cli("train broccoli --data " + shell_quoted(seq()) +
                   " --config broccoli-fec-uk --set outliers.enabled=false --out " + shell_quoted(model) + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_cli("bench broccoli --data " + shell_quoted(seq()) + " --model " + shell_quoted(model) +
              " --frames 2 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* p : {"oes", "org", "fec", "pcl_reference"}) {
    ASSERT_TRUE(j["pipelines"].contains(p)) << p;
    EXPECT_GT(j["pipelines"][p]["fps"].get<double>(), 0.0) << p;
    EXPECT_TRUE(j["pipelines"][p]["stages_ms"].contains("normals")) << p;
  }
  EXPECT_TRUE(j["pipelines"]["oes"].contains("speedup_vs_pcl"));
  // The model's own pipeline (FEC) runs with the settings the model records, the others with presets.
  EXPECT_EQ(j["settings"]["fec"], "model");
  EXPECT_EQ(j["settings"]["oes"], "preset broccoli-oes-uk");
}

// bench --track (the tracking timing target on the pipeline's own frames): the sizing + tracking time
// of the OES detections, with the --set sizing keys it ran under; --pipelines picks what is timed.
TEST_F(BroccoliCli, BenchTrackTimesSizingOnTheOesDetections) {
  const fs::path model = dir() / "bench-track.json";
  auto r = run_cli("train broccoli --data " + shell_quoted(seq()) +
                   " --config broccoli-oes-uk --set detection.grow_tolerance=0.013 --out " + shell_quoted(model) +
                   " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string base =
      "bench broccoli --data " + shell_quoted(seq()) + " --model " + shell_quoted(model) + " --frames 2";
  r = run_cli(base + " --pipelines oes --track --json --set sizing.hull_max_points=500 --set tracking.use_poses=true");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["pipelines"].size(), 1u);
  ASSERT_TRUE(j["pipelines"].contains("oes"));
  // The model's settings, not the preset's: its head completion is timed.
  EXPECT_EQ(j["settings"]["oes"], "model");
  EXPECT_TRUE(j["pipelines"]["oes"]["stages_ms"].contains("completion"));
  EXPECT_FALSE(j["pipelines"]["oes"].contains("speedup_vs_pcl"));  // no PCL run to compare with
  ASSERT_TRUE(j.contains("tracking"));
  const auto& t = j["tracking"];
  EXPECT_GT(t["detections_per_frame"].get<double>(), 0.0);  // the fixture's frames hold heads
  EXPECT_GT(t["ms_per_frame"].get<double>(), 0.0);
  EXPECT_GT(t["ratio_to_oes"].get<double>(), 0.0);
  EXPECT_EQ(t["sizing"]["hull_max_points"].get<int>(), 500);
  EXPECT_TRUE(t["use_poses"].get<bool>());
  // Without --track no tracking section; the text form names the sizing line.
  r = run_cli(base + " --pipelines oes,org --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(nlohmann::json::parse(r.out).contains("tracking"));
  EXPECT_EQ(nlohmann::json::parse(r.out)["pipelines"].size(), 2u);
  r = run_cli(base + " --pipelines oes --track");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("sizing + tracking"), std::string::npos) << r.out;
  // Bad selections: one line naming the option.
  for (const char* bad : {" --pipelines oes,pcll", " --pipelines org --track", " --pipelines oes,,org"}) {
    r = run_cli(base + bad);
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(r.err.find("--pipelines") != std::string::npos || r.err.find("--track") != std::string::npos) << r.err;
  }
}

// A preset may carry the sizing.* / tracking.* keys (detect/eval --track read them):
// train and bench must split them off before configuring the detector, and still reject typos.
TEST_F(BroccoliCli, TrainAndBenchIgnoreTrackingKeysOfAPreset) {
  const fs::path preset = dir() / "with-tracking.yaml";
  {
    std::ofstream f(preset);
    f << "pipeline: oes\nfeatures: vfh\noes:\n  min_size: 500\nsizing:\n  estimator: hull\n"
         "  bbox_offset_mm: 12.5\ntracking:\n  use_poses: true\n";
  }
  const fs::path model = dir() / "tracking-keys.json";
  auto r = run_cli("train broccoli --data " + shell_quoted(seq()) + " --config " + shell_quoted(preset) + " --out " +
                   shell_quoted(model) + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const learning::Model m = learning::load_model(model);
  for (const auto& [k, v] : m.info.config) {
    EXPECT_NE(k.rfind("sizing.", 0), 0u) << k;
    EXPECT_NE(k.rfind("tracking.", 0), 0u) << k;
  }
  r = run_cli("bench broccoli --data " + shell_quoted(seq()) + " --model " + shell_quoted(model) +
              " --frames 1 --json --set tracking.use_poses=true --set sizing.estimator=bbox");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(nlohmann::json::parse(r.out)["pipelines"].contains("oes"));
  // A misspelt tracking key is still an error, with one line.
  r = run_cli("train broccoli --data " + shell_quoted(seq()) + " --config " + shell_quoted(preset) +
              " --set tracking.no_such_key=1 --out " + shell_quoted(dir() / "typo.json"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no_such_key"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir() / "typo.json"));
  r = run_cli("bench broccoli --data " + shell_quoted(seq()) + " --model " + shell_quoted(model) +
              " --frames 1 --set sizing.estimmator=x");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("estimmator"), std::string::npos) << r.err;
}

// Outputs that would destroy or hide data are refused before any work, with one line naming them.
TEST_F(BroccoliCli, OutputsNeverDestroyUnrelatedFilesAndBadOptionsAreRefused) {
  const fs::path model = dir() / "outputs.json";
  auto r = run_cli("train broccoli --data " + shell_quoted(seq()) + " --config broccoli-oes-uk --out " +
                   shell_quoted(model) + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string base =
      "detect broccoli --data " + shell_quoted(seq()) + " --model " + shell_quoted(model) + " --quiet --out ";

  // --masks is written whole: a folder cropsight did not write is refused, untouched.
  const fs::path docs = dir() / "docs";
  fs::create_directories(docs / "sub");
  std::ofstream(docs / "notes.txt") << "keep me\n";
  r = run_cli(base + shell_quoted(dir() / "d1.jsonl") + " --masks " + shell_quoted(docs));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("not written by cropsight"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(docs / "notes.txt"));
  EXPECT_TRUE(fs::exists(docs / "sub"));
  EXPECT_FALSE(fs::exists(dir() / "d1.jsonl"));
  // A previous run's masks (and a trailing slash) are replaced with --force, and no temporary is left.
  const fs::path masks = dir() / "masks2";
  r = run_cli(base + shell_quoted(dir() / "d2.jsonl") + " --masks " + shell_quoted(masks));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_cli(base + shell_quoted(dir() / "d2.jsonl") + " --masks " + shell_quoted(masks.string() + "/"));
  EXPECT_EQ(r.exit_code, 2) << "an earlier output is replaced only with --force";
  r = run_cli(base + shell_quoted(dir() / "d2.jsonl") + " --masks " + shell_quoted(masks.string() + "/") + " --force");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(masks / "000005.png"));
  for (const auto& e : fs::directory_iterator(dir()))
    EXPECT_EQ(e.path().filename().string().find(".masks2."), std::string::npos) << e.path();

  // --out naming a directory: said so (it used to read "cannot write: Success").
  r = run_cli(base + shell_quoted(docs));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("is a folder"), std::string::npos) << r.err;

  // Counts and ranges: errors, not silent defaults.
  r = run_cli("bench broccoli --data " + shell_quoted(seq()) + " --model " + shell_quoted(model) +
              " --frames 100 --json");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--frames"), std::string::npos) << r.err;
  r = run_cli("bench broccoli --data " + shell_quoted(seq()) + " --model " + shell_quoted(model) +
              " --frames -1 --json");
  EXPECT_EQ(r.exit_code, 2);
  r = run_cli("eval broccoli --data " + shell_quoted(seq()) + " --model " + shell_quoted(model) +
              " --track --map-min-points -1 --quiet");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--map-min-points"), std::string::npos) << r.err;
  r = run_cli(base + shell_quoted(dir() / "d3.jsonl") + " --set depth.min_depth=-5");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("depth.min_depth"), std::string::npos) << r.err;
  r = run_cli(base + shell_quoted(dir() / "d3.jsonl") + " --track --set tracking.position_cap_m=-1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("tracking.position_cap_m"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir() / "d3.jsonl"));

  // --track compares with groundtruth.json: without it the map figures would silently read 0.
  const fs::path no_truth = dir() / "seq-no-truth";
  fs::copy(seq(), no_truth, fs::copy_options::recursive);
  fs::remove(no_truth / "groundtruth.json");
  r = run_cli("eval broccoli --data " + shell_quoted(no_truth) + " --model " + shell_quoted(model) +
              " --track --quiet");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("groundtruth.json"), std::string::npos) << r.err;

  // report: settings only drive the detection sections, so without --model they are an error.
  r = run_cli("report --data " + shell_quoted(seq()) + " --out " + shell_quoted(dir() / "r.html") +
              " --set oes.min_size=nan");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--model"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir() / "r.html"));

  // A damaged model: half of the SVM cut away loads no more (it used to give 4x the detections).
  auto j = nlohmann::json::parse(std::ifstream(model));
  const std::string payload = j["payload"];
  j["payload"] = payload.substr(0, payload.size() / 2);
  std::ofstream(dir() / "half.json") << j.dump();
  r = run_cli("detect broccoli --data " + shell_quoted(seq()) + " --model " + shell_quoted(dir() / "half.json") +
              " --quiet --out " + shell_quoted(dir() / "d4.jsonl"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("half.json"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("truncated"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;  // libsvm printed nothing
}

// Randomised fields from the CLI: --variety random / random-wide and --randomize
// draw a field and record it in groundtruth.json; a malformed range is one error line, exit 2.
TEST_F(BroccoliCli, SimulateRandomizedFields) {
  for (const std::string opts : {"--variety random", "--variety random-wide", "--variety spain --randomize"}) {
    const fs::path out = dir() / ("rand-" + std::to_string(std::hash<std::string>{}(opts)));
    auto r = run_cli("simulate broccoli " + opts + " --seed 9 --frames 1 --json --out " + shell_quoted(out));
    ASSERT_EQ(r.exit_code, 0) << opts << ": " << r.err;
    const auto gt = nlohmann::json::parse(io::read_file(out / "groundtruth.json"));
    EXPECT_EQ(gt["attributes"]["randomized"], "1") << opts;
  }
  auto r = run_cli("simulate broccoli --variety random --frames 1 --set randomize.camera_height_m=[1.5,1.1] --out " +
                   shell_quoted(dir() / "bad-range"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("camera_height_m"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir() / "bad-range"));
}

// cropsight import (Deliver 4): a RealSense-style folder pair (rs-convert names whose
// depth and colour timestamps differ) becomes a sequence that detect broccoli runs on without
// ground truth; a bad image is one line naming it, exit 2, and no output folder.
TEST_F(BroccoliCli, ImportRecordingThenDetect) {
  const fs::path rec = dir() / "recording";
  fs::create_directories(rec / "depth");
  fs::create_directories(rec / "color");
  for (int i = 0; i < 3; ++i) {
    const std::string stamp = std::to_string(1596203844000 + 133 * i);
    fs::copy_file(seq() / "depth" / io::frame_file_name(i), rec / "depth" / ("_Depth_" + stamp + ".250.png"));
    fs::copy_file(seq() / "color" / io::frame_file_name(i), rec / "color" / ("_Color_" + stamp + "7.5.png"));
  }
  const fs::path out = dir() / "imported";
  auto r = run_cli("import --depth " + shell_quoted(rec / "depth") + " --color " + shell_quoted(rec / "color") +
                   " --camera " + shell_quoted(seq() / "camera.yaml") + " --out " + shell_quoted(out) + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["frames"], 3);
  EXPECT_TRUE(j["color"].get<bool>());
  EXPECT_TRUE(j["timestamps_from_names"].get<bool>());
  for (int i = 0; i < 3; ++i)
    EXPECT_EQ(io::read_file(out / "depth" / io::frame_file_name(i)),
              io::read_file(seq() / "depth" / io::frame_file_name(i)));
  EXPECT_FALSE(fs::exists(out / "groundtruth.json"));
  const fs::path model = cropsight::testing::source_dir() / "models" / "broccoli-oes-uk.json";
  r = run_cli("detect broccoli --data " + shell_quoted(out) + " --model " + shell_quoted(model) + " --out " +
              shell_quoted(dir() / "imported.jsonl"));
  EXPECT_EQ(r.exit_code, 0) << r.err;

  // Organised PCDs (as `cropsight export` writes them) import to the same depth, +-1 raw unit.
  fs::create_directories(rec / "pcd");
  for (int i = 0; i < 2; ++i) {
    r = run_cli("export --data " + shell_quoted(seq()) + " --frame " + std::to_string(i) + " --out " +
                shell_quoted(rec / "pcd" / ("cloud_" + std::to_string(i) + ".pcd")));
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  r = run_cli("import --pcd " + shell_quoted(rec / "pcd") + " --camera " + shell_quoted(seq() / "camera.yaml") +
              " --out " + shell_quoted(dir() / "imported-pcd"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  {
    io::SequenceReader a(seq()), b(dir() / "imported-pcd");
    ASSERT_EQ(b.size(), 2);
    const RgbdFrame fa = a.read(1), fb = b.read(1);
    int off = 0;
    for (std::size_t i = 0; i < fa.depth.data.size(); ++i)
      off += std::abs(int(fa.depth.data[i]) - int(fb.depth.data[i])) > 1;
    EXPECT_EQ(off, 0);
  }

  // A colour PNG among the depth images: one line naming it, exit 2, nothing written.
  fs::copy_file(seq() / "color" / io::frame_file_name(0), rec / "depth" / "_Depth_1596203999000.000.png");
  r = run_cli("import --depth " + shell_quoted(rec / "depth") + " --camera " + shell_quoted(seq() / "camera.yaml") +
              " --out " + shell_quoted(dir() / "bad-import"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("_Depth_1596203999000.000.png"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(dir() / "bad-import"));
  for (const auto& e : fs::directory_iterator(dir()))
    EXPECT_EQ(e.path().filename().string().find("bad-import"), std::string::npos) << e.path();
}
