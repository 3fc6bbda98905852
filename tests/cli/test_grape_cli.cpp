// End-to-end checks of the grape sub-commands through the CLI binary (skipped until it is built).
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "cropsight/io/files.hpp"
#include "cropsight/io/grape_text.hpp"
#include "pipeline/grape/grape_test_clouds.hpp"
#include "testing/testing.hpp"

namespace {
using namespace cropsight;

// `n` two-blob clouds as DIR/points/c<i>.txt, the layout `--data DIR` reads.
void write_blob_clouds(const std::filesystem::path& dir, int n) {
  std::filesystem::create_directories(dir / "points");
  for (int i = 0; i < n; ++i)
    io::write_grape_text(dir / "points" / ("c" + std::to_string(i) + ".txt"),
                         cropsight::testing::two_blobs(std::uint32_t(i)));
}

TEST(GrapeCli, TrainEvalSegmentAndBadInput) {
  if (!std::filesystem::exists(cropsight::testing::cli_path())) GTEST_SKIP() << "CLI not built";
  cropsight::testing::TempDir t;
  write_blob_clouds(t / "data", 4);
  const std::string data = (t / "data").string(), model = (t / "m.json").string();
  auto r = cropsight::testing::run_cli("train grape --clouds '" + data + "' --model gbdt --val-fold 1/2 --out '" +
                                       model + "' --set gbdt.rounds=5 --set points_per_cloud=300 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = cropsight::testing::run_cli("eval grape --clouds '" + data + "' --model '" + model + "' --fold 1/2 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* k : {"clouds", "points", "oacc", "macc", "miou", "per_class", "ms_per_cloud"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_EQ(j["clouds"], 2);
  EXPECT_EQ(j["per_class"].size(), 6u);
  // The named protocols beside the old keys (grape/eval.hpp); the pooled six-label one is `miou`.
  for (const char* p : {"pooled_all_labels", "pooled_named_classes", "per_cloud_named_classes", "per_cloud_all_labels"})
    EXPECT_TRUE(j["protocols"].contains(p)) << p;
  EXPECT_EQ(j["protocols"]["pooled_all_labels"]["miou"], j["miou"]);
  EXPECT_EQ(j["protocols"]["pooled_named_classes"]["classes"], (std::vector<int>{1, 2, 3, 4, 5}));
  r = cropsight::testing::run_cli("segment grape --model '" + model + "' --clouds '" + data +
                                  "/points/c0.txt' --out '" + (t / "lab.txt").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(io::read_grape_text(t / "lab.txt").size(), 400u);
  // The paper's sampled mode is a network option; a GBDT recipe samples by itself.
  r = cropsight::testing::run_cli("eval grape --clouds '" + data + "' --model '" + model + "' --sampled --json");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("'sampled'"), std::string::npos) << r.err;  // errors name the segmenter's config keys
  // So are --votes (test-time augmentation) and its range.
  for (const char* votes : {"2", "0"}) {
    r = cropsight::testing::run_cli("eval grape --clouds '" + data + "' --model '" + model + "' --votes " + votes);
    EXPECT_EQ(r.exit_code, 2) << votes;
    EXPECT_NE(r.err.find("'votes'"), std::string::npos) << r.err;
  }
  // An ensemble with itself runs; a weight without a partner, or out of range, is an error.
  r = cropsight::testing::run_cli("eval grape --clouds '" + data + "' --model '" + model + "' --ensemble '" + model +
                                  "' --ensemble-weight 0.3 --fold 1/2 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto je = nlohmann::json::parse(r.out);
  EXPECT_EQ(je["clouds"], j["clouds"]);
  EXPECT_EQ(je["ensemble_weight"], 0.3);
  EXPECT_EQ(je["votes"], 1);
  for (const char* bad : {" --ensemble-weight 0.3", " --ensemble-weight 2 --ensemble '__M__'"}) {
    std::string args = std::string("eval grape --clouds '") + data + "' --model '" + model + "'" + bad;
    if (const auto at = args.find("__M__"); at != std::string::npos) args.replace(at, 5, model);
    r = cropsight::testing::run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_NE(r.err.find("'ensemble_weight'"), std::string::npos) << r.err;
  }

  std::ofstream(t / "bad.txt") << "1 2 3\n";
  r = cropsight::testing::run_cli("segment grape --model '" + model + "' --clouds '" + (t / "bad.txt").string() +
                                  "' --out '" + (t / "never.txt").string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("bad.txt: line 1"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(t / "never.txt"));
}

// The network presets say `threads: 2`; an explicit --threads must still win (it once did not:
// --threads 1 trained on two threads), and --set threads=... applies when --threads is absent.
TEST(GrapeCli, ExplicitThreadsOverrideThePreset) {
  if (!std::filesystem::exists(cropsight::testing::cli_path())) GTEST_SKIP() << "CLI not built";
  cropsight::testing::TempDir t;
  write_blob_clouds(t / "data", 2);
  const std::string base = "train grape --clouds '" + (t / "data").string() +
                           "' --model pointresnet --features xyz --epochs 1 --force --out '" + (t / "n.pt").string() +
                           "' --set num_points=64 --set sa1_points=16 --set sa2_points=8 --set sa3_points=4 "
                           "--set width=4 --set batch_size=2 --set val_every=0";
  auto r = cropsight::testing::run_cli(base + " --threads 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("training clouds, 1 thread\n"), std::string::npos) << r.err;
  r = cropsight::testing::run_cli(base);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("training clouds, 2 threads"), std::string::npos) << r.err;
  r = cropsight::testing::run_cli(base + " --set threads=1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("training clouds, 1 thread\n"), std::string::npos) << r.err;
  r = cropsight::testing::run_cli(base + " --threads -1");
  EXPECT_EQ(r.exit_code, 2) << r.err;

  // Both network modes through eval: every point, and the paper's sampled mode.
  for (const std::string mode : {"every-point", "sampled"}) {
    r = cropsight::testing::run_cli("eval grape --clouds '" + (t / "data").string() + "' --model '" +
                                    (t / "n.pt").string() + "'" + (mode == "sampled" ? " --sampled" : "") + " --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["mode"], mode);
    EXPECT_EQ(j["points"], 800);
  }
}
// The shipped best recipe as a preset: `segment grape` without --model runs configs/grape-best.yaml,
// and it labels exactly as the flags it stands for; --config plus a flag overrides that one key;
// a bad value names the preset file and the key.
TEST(GrapeCli, SegmenterPresetsEqualTheirFlags) {
  if (!std::filesystem::exists(cropsight::testing::cli_path())) GTEST_SKIP() << "CLI not built";
  const auto models = cropsight::testing::source_dir() / "models";
  if (!std::filesystem::exists(models / "grape-pointresnet.pt")) GTEST_SKIP() << "shipped models absent";
  cropsight::testing::TempDir t;
  write_blob_clouds(t / "data", 1);
  const std::string in = " --clouds '" + (t / "data" / "points" / "c0.txt").string() + "' --out '";
  auto segment = [&](const std::string& args, const std::string& out) {
    const auto r = cropsight::testing::run_cli("segment grape" + args + in + (t / out).string() + "' --json");
    EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err;
    return io::read_file(t / out);
  };
  const std::string m = " --model '" + (models / "grape-pointresnet.pt").string() + "'";
  const std::string flags = m + " --sampled --votes 6 --ensemble '" + (models / "grape-gbdt-fast4096.json").string() +
                            "' --ensemble-weight 0.5";
  EXPECT_EQ(segment("", "default.txt"), segment(flags, "flags.txt"));
  EXPECT_EQ(segment(" --config grape-best", "preset.txt"), io::read_file(t / "flags.txt"));
  // The paper-faithful preset: PointResNet alone, one pass, nearest neighbour; --votes overrides.
  EXPECT_EQ(segment(" --config grape-paper", "paper.txt"), segment(m + " --sampled --carry-k 1", "paper-flags.txt"));
  EXPECT_EQ(segment(" --config grape-paper --votes 2", "paper2.txt"),
            segment(m + " --sampled --carry-k 1 --votes 2", "paper2-flags.txt"));
  std::ofstream(t / "bad.yaml") << "model: x.pt\nvotes: 0\n";
  auto r = cropsight::testing::run_cli("segment grape --config '" + (t / "bad.yaml").string() + "'" + in +
                                       (t / "never.txt").string() + "'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("bad.yaml: 'votes' must be at least 1"), std::string::npos) << r.err;
  r = cropsight::testing::run_cli("segment grape --config grape-best --carry-k 0" + in + (t / "never.txt").string() +
                                  "'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("command line: 'carry_k' must be at least 1"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(t / "never.txt"));
}
}  // namespace
