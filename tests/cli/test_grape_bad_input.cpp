// Bad input to the grape sub-commands through the CLI binary (skipped until it is built): each
// case must end with exit 2, one line naming the file or option and the problem, no crash or
// hang, and no partial output left behind.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "cropsight/core/camera.hpp"
#include "cropsight/core/image.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/grape_text.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/sequence.hpp"
#include "pipeline/grape/grape_test_clouds.hpp"
#include "testing/testing.hpp"

namespace {
using namespace cropsight;
using cropsight::testing::run_cli;
using cropsight::testing::shell_quoted;
namespace fs = std::filesystem;

void write_clouds(const fs::path& dir, int n) {
  fs::create_directories(dir / "points");
  for (int i = 0; i < n; ++i)
    io::write_grape_text(dir / "points" / ("c" + std::to_string(i) + ".txt"),
                         cropsight::testing::two_blobs(std::uint32_t(i), 200));
}

// A tiny network that trains in well under a second.
const std::string kTinyNet =
    " --model pointresnet --features xyz --epochs 1 --set num_points=64 --set sa1_points=16 --set sa2_points=8"
    " --set sa3_points=4 --set width=4 --set batch_size=2 --set val_every=0 --threads 1";

// Exit 2 and a last stderr line "cropsight: ..." holding every `parts`, without a stack trace.
void expect_one_line_error(const cropsight::testing::CommandResult& r, const std::vector<std::string>& parts,
                           const std::string& what) {
  EXPECT_EQ(r.exit_code, 2) << what << "\n" << r.err;
  std::string last = r.err;
  while (!last.empty() && last.back() == '\n') last.pop_back();
  last = last.substr(last.rfind('\n') == std::string::npos ? 0 : last.rfind('\n') + 1);
  EXPECT_EQ(last.rfind("cropsight: ", 0), 0u) << what << "\n" << r.err;
  for (const auto& p : parts) EXPECT_NE(last.find(p), std::string::npos) << what << ": '" << p << "'\n" << r.err;
  EXPECT_EQ(r.err.find("Exception raised"), std::string::npos) << what << "\n" << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << what << "\n" << r.err;
  EXPECT_EQ(r.err.find("Stack trace"), std::string::npos) << what << "\n" << r.err;
}

// Files whose names start with `.` and hold "tmp": the writers' temporaries.
int temporaries_in(const fs::path& dir) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().find("tmp") != std::string::npos) ++n;
  return n;
}

class GrapeBadInput : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(cropsight::testing::cli_path())) GTEST_SKIP() << "CLI not built";
    write_clouds(t / "data", 3);
    data = shell_quoted(t / "data");
  }
  // A small GBDT (trained once per test that needs it).
  std::string gbdt_model() {
    const fs::path m = t / "m.json";
    if (!fs::exists(m)) {
      const auto r = run_cli("train grape --clouds " + data + " --model gbdt --out " + shell_quoted(m) +
                             " --set gbdt.rounds=2 --set points_per_cloud=100 --threads 1");
      EXPECT_EQ(r.exit_code, 0) << r.err;
    }
    return shell_quoted(m);
  }
  cropsight::testing::TempDir t;
  std::string data;
};

// The networks' libtorch backend is a plugin loaded on first use (src/nn/segmenter_backend.hpp).
// Without it a network command ends with one line that says how to point at it, and leaves no
// output; the GBDT commands never need it. (This test's process only: ctest runs each test alone.)
TEST_F(GrapeBadInput, MissingNetworkBackendIsOneLineAndGbdtNeedsNone) {
  ASSERT_EQ(setenv("CROPSIGHT_NN_BACKEND", (t / "no" / "libcropsight_nn_torch.so").c_str(), 1), 0);
  const fs::path out = t / "net.pt";
  expect_one_line_error(run_cli("train grape --clouds " + data + kTinyNet + " --out " + shell_quoted(out)),
                        {"network backend", "CROPSIGHT_NN_BACKEND"}, "train without backend");
  EXPECT_FALSE(fs::exists(out));
  // A file that is no backend (here a model file) is named as such.
  const std::string model = gbdt_model();  // trains and, below, segments without the backend
  ASSERT_EQ(setenv("CROPSIGHT_NN_BACKEND", (t / "m.json").c_str(), 1), 0);
  expect_one_line_error(run_cli("train grape --clouds " + data + kTinyNet + " --out " + shell_quoted(out)),
                        {"m.json", "network backend"}, "a file that is no backend");
  const auto r = run_cli("segment grape --model " + model + " --clouds " +
                         shell_quoted(t / "data" / "points" / "c0.txt") + " --out " + shell_quoted(t / "seg.txt"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(t / "seg.txt"));
  unsetenv("CROPSIGHT_NN_BACKEND");
}

// Bug: --threads 100000 crashed (OpenMP / XGBoost) or hung (libtorch); 0 and -1 passed silently.
TEST_F(GrapeBadInput, ThreadsOutOfRange) {
  const std::string model = gbdt_model();
  const std::string cloud = shell_quoted(t / "data" / "points" / "c0.txt");
  for (const char* n : {"100000", "0", "-1"}) {
    expect_one_line_error(run_cli("segment grape --model " + model + " --clouds " + cloud + " --out " +
                                  shell_quoted(t / "o.txt") + " --threads " + n),
                          {"--threads", "1..256"}, std::string("segment ") + n);
    expect_one_line_error(run_cli("eval grape --clouds " + data + " --model " + model + " --threads " + n),
                          {"--threads", "1..256"}, std::string("eval ") + n);
    expect_one_line_error(run_cli("train grape --clouds " + data + " --model gbdt --out " + shell_quoted(t / "x.json") +
                                  " --threads " + n),
                          {"--threads", "1..256"}, std::string("train ") + n);
  }
  // The presets' fields too.
  expect_one_line_error(run_cli("train grape --clouds " + data + " --model gbdt --out " + shell_quoted(t / "x.json") +
                                " --set gbdt.nthread=100000"),
                        {"'gbdt.nthread'"}, "gbdt.nthread");
  expect_one_line_error(run_cli("train grape --clouds " + data + " --model gbdt --out " + shell_quoted(t / "x.json") +
                                " --set features.threads=0"),
                        {"'features.threads'"}, "features.threads");
  std::string net = kTinyNet;
  net.erase(net.find(" --threads 1"));
  expect_one_line_error(
      run_cli("train grape --clouds " + data + net + " --out " + shell_quoted(t / "n.pt") + " --set threads=0"),
      {"'threads'"}, "net threads");
  EXPECT_FALSE(fs::exists(t / "o.txt"));
  EXPECT_FALSE(fs::exists(t / "x.json"));
  EXPECT_FALSE(fs::exists(t / "n.pt"));
}

// Bug: batch_size=0 crashed, batch_size=-1 trained; lr=-1, k1=0, dropout=2, width=0 gave
// libtorch stack traces. Every field is named.
TEST_F(GrapeBadInput, NetworkConfigFields) {
  // (Each field's range is checked in tests/nn/test_point_segmenter.cpp; here, that the CLI names it.)
  for (const std::string kv : {"batch_size=0", "batch_size=-1", "lr=-1", "k1=0", "dropout=2", "width=0"}) {
    const std::string key = kv.substr(0, kv.find('='));
    expect_one_line_error(
        run_cli("train grape --clouds " + data + kTinyNet + " --out " + shell_quoted(t / "n.pt") + " --set " + kv),
        {"--config/--set", "'" + key + "'"}, kv);
  }
  for (const std::string kv :
       {"gbdt.rounds=0", "gbdt.eta=0", "gbdt.subsample=1.5", "gbdt.max_depth=0", "features.k_small=1"}) {
    const std::string key = kv.substr(0, kv.find('='));
    expect_one_line_error(
        run_cli("train grape --clouds " + data + " --model gbdt --out " + shell_quoted(t / "m.json") + " --set " + kv),
        {"--config/--set", "'" + key + "'"}, kv);
  }
  EXPECT_FALSE(fs::exists(t / "n.pt"));
  EXPECT_FALSE(fs::exists(t / "m.json"));
}

// Bug: --limit 0 / -5 meant all clouds, --epochs 0 / -1 the preset's, --folds -2 printed
// "clouds 0, OAcc nan", and a fold holding no cloud evaluated nothing, all with exit 0.
TEST_F(GrapeBadInput, CountsAndFolds) {
  const std::string train = "train grape --clouds " + data + " --model gbdt --out " + shell_quoted(t / "x.json");
  for (const char* n : {"0", "-5"}) expect_one_line_error(run_cli(train + " --limit " + n), {"--limit"}, n);
  for (const char* n : {"0", "-1"})
    expect_one_line_error(
        run_cli("train grape --clouds " + data + kTinyNet + " --out " + shell_quoted(t / "n.pt") + " --epochs " + n),
        {"--epochs"}, n);
  for (const char* n : {"-2", "0", "1"}) expect_one_line_error(run_cli(train + " --folds " + n), {"--folds"}, n);
  expect_one_line_error(run_cli(train + " --folds 4"), {"--folds", "4 folds need at least 4 clouds", "has 3"},
                        "folds 4");
  expect_one_line_error(run_cli(train + " --val-fold 5/5"), {"--val-fold", "has 3"}, "val-fold 5/5");
  EXPECT_FALSE(fs::exists(t / "x.json"));
  const std::string model = gbdt_model();
  for (const char* n : {"0", "-5"})
    expect_one_line_error(run_cli("eval grape --clouds " + data + " --model " + model + " --limit " + n), {"--limit"},
                          n);
  expect_one_line_error(run_cli("eval grape --clouds " + data + " --model " + model + " --fold 5/5"),
                        {"--fold", "5 folds need at least 5 clouds", "has 3"}, "fold 5/5");
  expect_one_line_error(run_cli("eval grape --clouds " + data + " --model " + model + " --fold 2/2 --limit 1"),
                        {"--fold", "(after --limit)"}, "fold 2/2 limit 1");
  const auto r = run_cli("eval grape --clouds " + data + " --model " + model + " --fold 3/3 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["clouds"], 1);
}

// Bug: --out DIR failed only after training ("internal error: filesystem error: cannot rename")
// and left the model's temporary behind.
TEST_F(GrapeBadInput, OutputIsADirectory) {
  fs::create_directories(t / "o");
  expect_one_line_error(run_cli("train grape --clouds " + data + kTinyNet + " --out " + shell_quoted(t / "o")),
                        {(t / "o").string(), "is a directory"}, "network");
  expect_one_line_error(run_cli("train grape --clouds " + data + " --model gbdt --out " + shell_quoted(t / "o")),
                        {(t / "o").string(), "is a directory"}, "gbdt");
  expect_one_line_error(run_cli("segment grape --model " + gbdt_model() + " --clouds " +
                                shell_quoted(t / "data" / "points" / "c0.txt") + " --out " + shell_quoted(t / "o")),
                        {(t / "o").string(), "is a folder"}, "segment");
  EXPECT_EQ(temporaries_in(t.path()), 0);
  EXPECT_TRUE(fs::is_empty(t / "o"));
}

// Bug: a bad --checkpoint or model file gave libtorch's / XGBoost's multi-line stack trace
// ("internal error: PytorchStreamReader failed ..."), without the file's name.
TEST_F(GrapeBadInput, BadCheckpointAndModelFiles) {
  // --force: every run below writes n.pt again (the first one wrote it).
  const std::string train =
      "train grape --clouds " + data + kTinyNet + " --out " + shell_quoted(t / "n.pt") + " --force";
  auto r = run_cli(train + " --checkpoint " + shell_quoted(t / "ck.pt"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string good_net = io::read_file(t / "n.pt"), good_ck = io::read_file(t / "ck.pt");
  std::ofstream(t / "empty.pt").flush();
  std::ofstream(t / "trunc.pt", std::ios::binary) << good_ck.substr(0, good_ck.size() / 2);
  std::ofstream(t / "truncnet.pt", std::ios::binary) << good_net.substr(0, good_net.size() / 2);
  gbdt_model();
  const std::string gbdt_text = io::read_file(t / "m.json");
  std::ofstream(t / "trunc.json", std::ios::binary) << gbdt_text.substr(0, gbdt_text.size() / 2);
  fs::copy_file(t / "m.json", t / "gbdt-as-ck.pt");
  // Resumed by a network of another width (and by another arch): the weights do not fit.
  for (const char* ck : {"empty.pt", "trunc.pt", "gbdt-as-ck.pt", "truncnet.pt"})
    expect_one_line_error(run_cli(train + " --checkpoint " + shell_quoted(t / ck)), {(t / ck).string()}, ck);
  fs::copy_file(t / "ck.pt", t / "ck8.pt");
  expect_one_line_error(run_cli(train + " --set width=8 --checkpoint " + shell_quoted(t / "ck8.pt")),
                        {(t / "ck8.pt").string(), "do not fit"}, "width 8");
  std::string net2 = train;
  net2.replace(net2.find("pointresnet"), 11, "pointnet2");
  fs::copy_file(t / "ck.pt", t / "ck2.pt");
  expect_one_line_error(run_cli(net2 + " --checkpoint " + shell_quoted(t / "ck2.pt")), {(t / "ck2.pt").string()},
                        "pointnet2");

  // Model files: truncated network and GBDT, a broccoli model, an empty file.
  fs::copy_file(cropsight::testing::source_dir() / "models" / "broccoli-fec-uk.json", t / "broccoli.json");
  for (const char* m : {"truncnet.pt", "trunc.json", "broccoli.json", "empty.pt"}) {
    expect_one_line_error(run_cli("eval grape --clouds " + data + " --model " + shell_quoted(t / m)),
                          {(t / m).string()}, m);
    expect_one_line_error(
        run_cli("segment grape --model " + shell_quoted(t / m) + " --clouds " +
                shell_quoted(t / "data" / "points" / "c0.txt") + " --out " + shell_quoted(t / "o.txt")),
        {(t / m).string()}, m);
  }
  EXPECT_FALSE(fs::exists(t / "o.txt"));
}

// Bug: a GBDT model whose feature recipe (attribute cropsight.features) held a malformed value
// ended with "internal error" from std::stoi (exit 1), and "fpfh=true" read as false. Now: exit 2,
// one line naming the model file and the key; "fpfh=true" means the same as "fpfh=1".
TEST_F(GrapeBadInput, CorruptModelRecipeNamesTheFileAndKey) {
  gbdt_model();
  const std::string text = io::read_file(t / "m.json"), recipe = "k_small=16;k_large=64;fpfh=1";
  ASSERT_NE(text.find(recipe), std::string::npos) << "the default recipe is stored in the model";
  auto with_recipe = [&](const std::string& name, const std::string& replacement) {
    std::string edited = text;
    edited.replace(edited.find(recipe), recipe.size(), replacement);
    std::ofstream(t / name, std::ios::binary) << edited;
    return shell_quoted(t / name);
  };
  const std::string cloud = shell_quoted(t / "data" / "points" / "c0.txt");
  for (const auto& [name, replacement, key] : std::vector<std::tuple<std::string, std::string, std::string>>{
           {"abc.json", "k_small=abc;k_large=64;fpfh=1", "'k_small'"},
           {"maybe.json", "k_small=16;k_large=64;fpfh=maybe", "'fpfh'"},
       }) {
    const std::string model = with_recipe(name, replacement);
    expect_one_line_error(
        run_cli("segment grape --model " + model + " --clouds " + cloud + " --out " + shell_quoted(t / "o.txt")),
        {(t / name).string(), key}, "segment " + name);
    expect_one_line_error(run_cli("eval grape --clouds " + data + " --model " + model), {(t / name).string(), key},
                          "eval " + name);
  }
  EXPECT_FALSE(fs::exists(t / "o.txt"));
  // "fpfh=true" labels exactly as the "fpfh=1" the model was written with.
  const std::string as_true = with_recipe("true.json", "k_small=16;k_large=64;fpfh=true");
  auto r =
      run_cli("segment grape --model " + gbdt_model() + " --clouds " + cloud + " --out " + shell_quoted(t / "a.txt"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_cli("segment grape --model " + as_true + " --clouds " + cloud + " --out " + shell_quoted(t / "b.txt"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(io::read_file(t / "a.txt"), io::read_file(t / "b.txt"));
}

// Bug: label 9 surfaced as "confusion matrix: label out of range" without a file; colour 300
// was accepted (the format's colours are in [0, 1]).
TEST_F(GrapeBadInput, LabelAndColourOutOfRange) {
  const std::string line = "0.1 0.2 0.3 0 0 1 0.5 0.5 0.5 ";
  for (const auto& [name, text, want] : std::vector<std::tuple<std::string, std::string, std::string>>{
           {"label9.txt", line + "1\n" + line + "9\n", "line 2: label 9 is not a class of the dataset (0-5)"},
           {"colour.txt", "0.1 0.2 0.3 0 0 1 300 0.5 0.5 1\n", "line 1: colour value 300 is outside [0, 1]"},
           {"neg.txt", "0.1 0.2 0.3 0 0 1 0.5 -0.5 0.5 1\n", "line 1: colour value -0.5"}}) {
    write_clouds(t / name, 2);
    std::ofstream(t / name / "points" / "c9.txt") << text;
    expect_one_line_error(
        run_cli("train grape --clouds " + shell_quoted(t / name) + " --model gbdt --out " + shell_quoted(t / "x.json")),
        {"c9.txt: " + want}, name);
  }
  EXPECT_FALSE(fs::exists(t / "x.json"));
}

// Bug: --input DIR said "no points"; the help promised an optional label column. A folder of
// clouds is an input now; one that holds none is named.
TEST_F(GrapeBadInput, SegmentInputDirectoryAndHelp) {
  fs::create_directories(t / "empty");
  expect_one_line_error(run_cli("segment grape --model " + gbdt_model() + " --clouds " + shell_quoted(t / "empty") +
                                " --out " + shell_quoted(t / "o")),
                        {(t / "empty").string(), "holds no .txt, .ply or .pcd cloud"}, "dir");
  EXPECT_FALSE(fs::exists(t / "o"));
  const auto r = run_cli("segment grape --help");
  EXPECT_EQ(r.out.find("[label]"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("10 numbers"), std::string::npos) << r.out;
}

// Bug: the shipped network preset without --model failed with "unknown configuration key 'arch'".
TEST_F(GrapeBadInput, ModelDefaultsToThePresetsArch) {
  std::string args = kTinyNet;
  args.erase(args.find(" --model pointresnet"), 20);
  auto r = run_cli("train grape --config grape-pointresnet --data " + data + args + " --out " +
                   shell_quoted(t / "n.pt") + " --limit 2 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["model"], "pointresnet");
  expect_one_line_error(run_cli("train grape --config grape-pointresnet --model gbdt --data " + data + " --out " +
                                shell_quoted(t / "x.json")),
                        {"--model", "pointresnet"}, "gbdt with a network preset");
}

// roi-cloud: one 16x12 frame at 1 m, a bunch box and its peduncle.
class GrapeRoiBadInput : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(cropsight::testing::cli_path())) GTEST_SKIP() << "CLI not built";
    CameraIntrinsics cam;
    cam.width = 16, cam.height = 12, cam.fx = cam.fy = 20, cam.cx = 8, cam.cy = 6;
    io::write_camera_yaml(t / "camera.yaml", cam);
    io::write_u16(t / "d.png", Image<std::uint16_t>(16, 12, 1000));
    io::write_color(t / "c.png", ColorImage(16, 12, Rgb8{100, 150, 50}));
    std::ofstream(t / "det.json") << R"([{"bbox": [2, 4, 8, 6], "category_id": 1, "score": 0.9},
                                         {"bbox": [5, 1, 2, 2], "category_id": 2, "score": 0.9}])";
    base = "roi-cloud --color " + shell_quoted(t / "c.png") + " --depth " + shell_quoted(t / "d.png") + " --camera " +
           shell_quoted(t / "camera.yaml") + " --detections ";
  }
  std::string run_to(const fs::path& out, const std::string& extra = "", const std::string& det = "det.json") {
    last = run_cli(base + shell_quoted(t / det) + " --out " + shell_quoted(out) + extra);
    return last.err;
  }
  cropsight::testing::TempDir t;
  std::string base;
  cropsight::testing::CommandResult last;
};

TEST_F(GrapeRoiBadInput, ConfigValues) {
  for (const std::string kv : {"normal_k=100000000", "normal_k=0", "z_min=5 --set z_max=1", "bunch_category=-1",
                               "min_score=5", "z_min=-1", "peduncle_category=1"}) {
    run_to(t / "out", " --set " + kv);
    const std::string key = kv.find("z_max") != std::string::npos ? "z_max" : kv.substr(0, kv.find('='));
    expect_one_line_error(last, {"--config/--set", "'" + key + "'"}, kv);
  }
  EXPECT_FALSE(fs::exists(t / "out"));
}

TEST_F(GrapeRoiBadInput, BoxOutsideTheImageWarns) {
  std::ofstream(t / "far.json") << R"([{"bbox": [2, 4, 8, 6], "category_id": 1},
                                       {"bbox": [200, 400, 8, 6], "category_id": 1}])";
  run_to(t / "out", " --json", "far.json");
  ASSERT_EQ(last.exit_code, 0) << last.err;
  EXPECT_NE(last.err.find("warning: " + (t / "far.json").string() +
                          ": annotation 1: bbox [200, 400, 8, 6] lies "
                          "outside the 16x12 image"),
            std::string::npos)
      << last.err;
  const auto j = nlohmann::json::parse(last.out);
  EXPECT_EQ(j["outside_image"], 1);
  EXPECT_EQ(j["rois"].size(), 1u);
}

// A second run replaces the first run's set as a whole; a folder of other files is never touched.
TEST_F(GrapeRoiBadInput, OutputFolderIsReplacedWhole) {
  run_to(t / "out");
  ASSERT_EQ(last.exit_code, 0) << last.err;
  ASSERT_TRUE(fs::exists(t / "out" / "roi_000.txt"));
  std::ofstream(t / "none.json") << "[]";
  run_to(t / "out", "", "none.json");
  EXPECT_EQ(last.exit_code, 2) << "an earlier output is replaced only with --force";
  run_to(t / "out", " --force", "none.json");
  ASSERT_EQ(last.exit_code, 0) << last.err;
  EXPECT_FALSE(fs::exists(t / "out" / "roi_000.txt"));
  EXPECT_EQ(nlohmann::json::parse(io::read_file(t / "out" / "rois.json"))["rois"].size(), 0u);
  EXPECT_EQ(temporaries_in(t.path()), 0);

  fs::create_directories(t / "mine");
  std::ofstream(t / "mine" / "notes.txt") << "keep";
  expect_one_line_error(run_cli(base + shell_quoted(t / "det.json") + " --out " + shell_quoted(t / "mine")),
                        {(t / "mine").string(), "not written by cropsight"}, "foreign folder");
  EXPECT_TRUE(fs::exists(t / "mine" / "notes.txt"));
  // A file, and a folder under a file (cannot be created).
  expect_one_line_error(run_cli(base + shell_quoted(t / "det.json") + " --out " + shell_quoted(t / "c.png")),
                        {(t / "c.png").string(), "is an input"}, "file");
  expect_one_line_error(run_cli(base + shell_quoted(t / "det.json") + " --out " + shell_quoted(t / "c.png" / "o")),
                        {(t / "c.png" / "o").string(), "inside the input"}, "under a file");
  EXPECT_EQ(temporaries_in(t.path()), 0);
}
}  // namespace
