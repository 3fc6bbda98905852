// Bad-input CLI tests of the stereo / seedling commands: every bad file, option or key gets exit 2
// and one stderr line naming it (never an OpenCV "internal error", a hang or exit 0), and no
// output - not even a partial one - is left behind. Each CLI start costs ~1.5 s, so every check
// here is one representative call; the library tests at the end cover the rest of the ranges.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "cropsight/core/error.hpp"
#include "cropsight/sim/seedling/seedling_sim.hpp"
#include "cropsight/stereo/calibration.hpp"
#include "cropsight/stereo/disparity.hpp"
#include "cropsight/stereo/middlebury.hpp"
#include "cropsight/stereo/stereo_io.hpp"
#include "seedling_cli_fixture.hpp"
#include "testing/testing.hpp"

namespace fs = std::filesystem;
using cropsight::testing::CommandResult;
using cropsight::testing::run_cli;
using cropsight::testing::shell_quoted;

namespace {

class StereoBadInput : public SeedlingCliFixture<StereoBadInput> {
 public:
  static constexpr const char* kSimulateArgs = " --pairs 1 --seed 5 --calib-pairs 0 --quiet";

 protected:
  static void SetUpTestSuite() {
    SeedlingCliFixture::SetUpTestSuite();
    // Small textured pairs for the disparity checks (fast): 8-bit colour, 8-bit grey, 16-bit.
    cv::Mat c(48, 64, CV_8UC3), g(48, 64, CV_8UC1), w(48, 64, CV_16UC3);
    cv::randu(c, 0, 255);
    cv::randu(g, 0, 255);
    cv::randu(w, 0, 65535);
    cv::imwrite((dir() / "c.png").string(), c);
    cv::imwrite((dir() / "g.png").string(), g);
    cv::imwrite((dir() / "w16.png").string(), w);
  }
  static std::string pair_args() {
    return " --left " + shell_quoted(pair0() / "left.png") + " --right " + shell_quoted(pair0() / "right.png");
  }
  static std::string small_pair() {
    return " --left " + shell_quoted(dir() / "c.png") + " --right " + shell_quoted(dir() / "c.png");
  }
  // The error contract (one line naming `what`) and no OpenCV text.
  static void expect_error(const CommandResult& r, const std::string& what) {
    expect_one_line_error(r, what);
    EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("OpenCV"), std::string::npos) << r.err;
  }
  // A copy of the simulated data set whose pair_000/`file` is replaced by `write(path)`.
  template <class F>
  static fs::path data_with(const std::string& name, const std::string& file, F&& write) {
    const fs::path d = dir() / name;
    fs::remove_all(d);
    fs::copy(data(), d, fs::copy_options::recursive);
    write(d / "pair_000" / file);
    return d;
  }
  // Entries of `parent` whose name starts with "." (temporaries a writer left behind).
  static int hidden_entries(const fs::path& parent) {
    int n = 0;
    for (const auto& e : fs::directory_iterator(parent)) n += e.path().filename().string().rfind('.', 0) == 0;
    return n;
  }
};

}  // namespace

// Bug 1: simulate seedling writes through a temporary folder, refuses to overwrite without
// --force, and bounds its counts.
TEST_F(StereoBadInput, SimulateSeedlingRefusesExistingAndBadCounts) {
  const fs::path out = dir() / "sim";
  fs::remove_all(out);
  ASSERT_EQ(run_cli("simulate seedling --out " + shell_quoted(out) + " --pairs 2 --calib-pairs 0 --quiet").exit_code,
            0);
  ASSERT_TRUE(fs::exists(out / "pair_001"));
  // Rerun over it without --force: refused, old data set untouched.
  auto r = run_cli("simulate seedling --out " + shell_quoted(out) + " --pairs 1 --calib-pairs 0 --quiet");
  expect_error(r, "--force");
  EXPECT_TRUE(fs::exists(out / "pair_001"));
  // With --force and fewer pairs: the old pair_001 must not survive next to the new rig.yaml.
  r = run_cli("simulate seedling --out " + shell_quoted(out) + " --pairs 1 --calib-pairs 0 --quiet --force");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out / "pair_000" / "left.png"));
  EXPECT_TRUE(fs::exists(out / "rig.yaml"));
  EXPECT_FALSE(fs::exists(out / "pair_001"));
  EXPECT_EQ(hidden_entries(dir()), 0);  // no temporary or old copy left behind
  // --force never replaces a folder cropsight did not write.
  const fs::path other = dir() / "not_data";
  fs::create_directories(other);
  std::ofstream(other / "notes.txt") << "keep me\n";
  expect_error(run_cli("simulate seedling --out " + shell_quoted(other) + " --pairs 1 --calib-pairs 0 --quiet --force"),
               "not written by cropsight");
  EXPECT_TRUE(fs::exists(other / "notes.txt"));
  // Counts: at least one pair, bounded, checked before anything is written.
  const fs::path fresh = dir() / "fresh";
  expect_error(run_cli("simulate seedling --out " + shell_quoted(fresh) + " --pairs 0 --calib-pairs 0"), "--pairs");
  expect_error(run_cli("simulate seedling --out " + shell_quoted(fresh) + " --pairs 2000000000"), "--pairs");
  expect_error(run_cli("simulate seedling --out " + shell_quoted(fresh) + " --pairs 1 --calib-pairs -1"),
               "--calib-pairs");
  EXPECT_FALSE(fs::exists(fresh));
  EXPECT_EQ(hidden_entries(dir()), 0);
}

// Bug 2: when --out cannot be written, --mask and --top-view are not left behind either.
TEST_F(StereoBadInput, DetectSeedlingWritesNoOutputWhenOneFails) {
  std::ofstream(dir() / "plain_file") << "x";
  const fs::path mask = dir() / "d2_mask.png", top = dir() / "d2_top.png";
  const auto r = run_cli("detect seedling" + pair_args() + " --calib " + shell_quoted(data() / "rig.yaml") +
                         " --mask " + shell_quoted(mask) + " --top-view " + shell_quoted(top) + " --out " +
                         shell_quoted(dir() / "plain_file" / "result.json"));
  expect_error(r, "result.json");
  EXPECT_FALSE(fs::exists(mask));
  EXPECT_FALSE(fs::exists(top));
  EXPECT_EQ(hidden_entries(dir()), 0);
}

// Bug 3: search ranges and windows that would hang or exhaust memory are refused up front.
TEST_F(StereoBadInput, DisparityBoundsRangesAndWindows) {
  const fs::path out = dir() / "b3.png";
  expect_error(run_cli("stereo disparity" + small_pair() + " --max-disp 1048576 --out " + shell_quoted(out)),
               "--max-disp");
  auto r =
      run_cli("stereo disparity" + small_pair() + " --max-disp 128 --out " + shell_quoted(out));  // image is 64 px wide
  expect_error(r, "--max-disp");
  EXPECT_NE(r.err.find("width"), std::string::npos) << r.err;
  expect_error(run_cli("stereo disparity" + small_pair() +
                       " --max-disp 16 --set engine=opencv --set rank_radius=100000 "
                       "--out " +
                       shell_quoted(out)),
               "rank_radius");
  expect_error(run_cli("stereo disparity" + small_pair() + " --max-disp 16 --set num_disparities=1048576 --out " +
                       shell_quoted(out)),
               "num_disparities");
  EXPECT_FALSE(fs::exists(out));
}

// Bug 4: values OpenCV asserts on are caught with a message naming the option.
TEST_F(StereoBadInput, CalibrateAndOutputsRejectWhatOpenCvWouldAssertOn) {
  const std::string cal =
      "stereo calibrate --images " + shell_quoted(dir()) + " --out " + shell_quoted(dir() / "never.yaml");
  expect_error(run_cli(cal + " --square-mm inf"), "--square-mm");
  expect_error(run_cli(cal + " --square-mm 1e300"), "--square-mm");
  expect_error(run_cli(cal + " --board 2x2"), "--board");
  EXPECT_FALSE(fs::exists(dir() / "never.yaml"));
  // Outputs without an image extension, or folders.
  expect_error(run_cli("stereo disparity" + small_pair() + " --max-disp 16 --out " + shell_quoted(dir() / "noext")),
               "--out");
  expect_error(run_cli("stereo disparity" + small_pair() + " --max-disp 16 --out " + shell_quoted(dir())), "--out");
  const std::string det = "detect seedling" + pair_args() + " --calib " + shell_quoted(data() / "rig.yaml");
  expect_error(run_cli(det + " --mask " + shell_quoted(dir() / "mask_noext")), "--mask");
  expect_error(run_cli(det + " --top-view " + shell_quoted(dir())), "--top-view");
  EXPECT_FALSE(fs::exists(dir() / "noext"));
  EXPECT_FALSE(fs::exists(dir() / "mask_noext"));
}

// Bug 5: a lossy / 8-bit disparity file is refused; input images must be 8-bit and of one kind.
TEST_F(StereoBadInput, DisparityAndDetectCheckFormatsAndImageKinds) {
  const fs::path out = dir() / "d.jpg";
  expect_error(run_cli("stereo disparity" + small_pair() + " --max-disp 16 --out " + shell_quoted(out)), "--out");
  EXPECT_FALSE(fs::exists(out));
  const fs::path png = dir() / "b5.png";
  expect_error(run_cli("stereo disparity --left " + shell_quoted(dir() / "w16.png") + " --right " +
                       shell_quoted(dir() / "c.png") + " --max-disp 16 --out " + shell_quoted(png)),
               "w16.png");
  auto r = run_cli("stereo disparity --left " + shell_quoted(dir() / "g.png") + " --right " +
                   shell_quoted(dir() / "c.png") + " --max-disp 16 --out " + shell_quoted(png));
  expect_error(r, "c.png");
  EXPECT_NE(r.err.find("grey"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(png));
  // detect seedling: a 16-bit left image and a grey left with a colour right.
  const fs::path l16 = dir() / "left16.png", lgrey = dir() / "left_grey.png";
  const cv::Mat left = cv::imread((pair0() / "left.png").string(), cv::IMREAD_COLOR);
  cv::Mat wide, grey;
  left.convertTo(wide, CV_16U, 256);
  cv::cvtColor(left, grey, cv::COLOR_BGR2GRAY);
  cv::imwrite(l16.string(), wide);
  cv::imwrite(lgrey.string(), grey);
  const std::string rest = " --right " + shell_quoted(pair0() / "right.png") + " --calib " +
                           shell_quoted(data() / "rig.yaml") + " --out " + shell_quoted(dir() / "b5.json");
  expect_error(run_cli("detect seedling --left " + shell_quoted(l16) + rest), "left16.png");
  expect_error(run_cli("detect seedling --left " + shell_quoted(lgrey) + rest), "right.png");
  EXPECT_FALSE(fs::exists(dir() / "b5.json"));
}

namespace {
// Fake Middlebury folder: four 64x48 pairs; tsukuba's ground truth is `tsukuba_gt`.
fs::path fake_middlebury(const fs::path& root, const cv::Mat& tsukuba_gt) {
  const cv::Mat gt(48, 64, CV_8U, cv::Scalar(40));
  cv::Mat img(48, 64, CV_8UC3);
  cv::randu(img, 0, 255);
  for (const char* p : {"tsukuba", "venus", "teddy", "cones"}) {
    fs::create_directories(root / p);
    cv::imwrite((root / p / "left.png").string(), img);
    cv::imwrite((root / p / "right.png").string(), img);
    const bool pgm = std::string(p) == "tsukuba" || std::string(p) == "venus";
    cv::imwrite((root / p / (pgm ? "disp_left.pgm" : "disp_left.png")).string(),
                std::string(p) == "tsukuba" ? tsukuba_gt : gt);
  }
  return root;
}
}  // namespace

// Bug 6: eval stereo rejects a ground truth of the wrong depth and one with nothing to score.
TEST_F(StereoBadInput, EvalStereoRejectsBadGroundTruth) {
  auto r = run_cli("eval stereo --json --middlebury " +
                   shell_quoted(fake_middlebury(dir() / "mb16", cv::Mat(48, 64, CV_16U, cv::Scalar(40 * 256)))));
  expect_error(r, "disp_left.pgm");
  EXPECT_NE(r.err.find("16-bit"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
  r = run_cli("eval stereo --json --middlebury " +
              shell_quoted(fake_middlebury(dir() / "mb0", cv::Mat(48, 64, CV_8U, cv::Scalar(0)))));
  expect_error(r, "disp_left.pgm");
  EXPECT_NE(r.err.find("no valid pixel"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
}

// Bug 7: eval seedling rejects a 16-bit mask and a degenerate truth envelope.
TEST_F(StereoBadInput, EvalSeedlingRejectsBadTruth) {
  const fs::path m16 = data_with("mask16", "mask.png", [](const fs::path& p) {
    cv::Mat m = cv::imread(p.string(), cv::IMREAD_UNCHANGED), w;
    m.convertTo(w, CV_16U, 257);
    cv::imwrite(p.string(), w);
  });
  auto r = run_cli("eval seedling --no-opencv --json --data " + shell_quoted(m16));
  expect_error(r, "mask.png");
  EXPECT_TRUE(r.out.empty());
  const fs::path h0 = data_with("height0", "truth.json", [](const fs::path& p) {
    std::string t;
    {
      std::ifstream in(p);
      t.assign(std::istreambuf_iterator<char>(in), {});
    }
    const auto k = t.find("\"height_m\":");
    ASSERT_NE(k, std::string::npos);
    const auto e = t.find_first_of(",\n}", k);
    t = t.substr(0, k) + "\"height_m\": 0" + t.substr(e);
    std::ofstream(p) << t;
  });
  r = run_cli("eval seedling --no-opencv --json --data " + shell_quoted(h0));
  expect_error(r, "truth.json");
  EXPECT_NE(r.err.find("height_m"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
}

// Bug 8: out-of-range configuration values fail naming the key (and --set, not an image).
TEST_F(StereoBadInput, OutOfRangeConfigNamesTheKey) {
  const std::string det = "detect seedling" + pair_args() + " --calib " + shell_quoted(data() / "rig.yaml") +
                          " --out " + shell_quoted(dir() / "b8.json") + " --set ";
  for (const std::string& kv :
       {std::string("min_depth=5 --set max_depth=1"), std::string("gmm.tolerance=-1"),
        std::string("gmm.components=100000"), std::string("gmm.components=0"), std::string("min_depth=nan")}) {
    const auto r = run_cli(det + kv);
    const std::string key = kv.substr(kv.rfind("--set ") == std::string::npos ? 0 : kv.rfind("--set ") + 6);
    expect_error(r, "'" + key.substr(0, key.find('=')) + "'");
    EXPECT_NE(r.err.find("--set"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("left.png"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("seedling.yaml"), std::string::npos) << r.err;
  }
  EXPECT_FALSE(fs::exists(dir() / "b8.json"));
  const fs::path out = dir() / "b8.png";
  for (const std::string& kv :
       {std::string("p1=-5"), std::string("uniqueness_ratio=-5"), std::string("engine=bogus")}) {
    const auto r =
        run_cli("stereo disparity" + small_pair() + " --max-disp 16 --out " + shell_quoted(out) + " --set " + kv);
    expect_error(r, "'" + kv.substr(0, kv.find('=')) + "'");
    EXPECT_NE(r.err.find("--set"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("c.png"), std::string::npos) << r.err;
  }
  expect_error(
      run_cli("stereo disparity" + small_pair() + " --max-disp 16 --method sad --window 0 --out " + shell_quoted(out)),
      "--window");
  EXPECT_FALSE(fs::exists(out));
  // Calibration YAML: an unknown (misspelt) key is refused, naming the file and the key.
  const fs::path rig = dir() / "rig_extra.yaml";
  fs::copy_file(data() / "rig.yaml", rig, fs::copy_options::overwrite_existing);
  std::ofstream(rig, std::ios::app) << "baseline_mm: 60\n";
  const auto r = run_cli("detect seedling" + pair_args() + " --calib " + shell_quoted(rig));
  expect_error(r, "rig_extra.yaml");
  EXPECT_NE(r.err.find("baseline_mm"), std::string::npos) << r.err;
}

// Library side of the same checks.
namespace {
// Runs `f`, expecting a cropsight::Error whose message contains `what`.
template <class F>
void expect_throw_naming(F&& f, const std::string& what) {
  try {
    f();
    ADD_FAILURE() << "no error; expected one naming " << what;
  } catch (const cropsight::Error& e) {
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
  }
}
}  // namespace

TEST(StereoValidation, ConfigErrorsNameTheKey) {
  using namespace cropsight::stereo;
  DisparityConfig d;
  d.rank_radius = 100000;
  expect_throw_naming([&] { validate_disparity_config(d, "x", "disparity."); }, "'disparity.rank_radius'");
  d = DisparityConfig{};
  d.num_disparities = 1 << 20;
  expect_throw_naming([&] { validate_disparity_config(d, "x"); }, "'num_disparities'");
  // The range is bounded by the image width too.
  const cropsight::GrayImage img(64, 48, 7);
  d = DisparityConfig{};
  d.num_disparities = 128;
  expect_throw_naming([&] { compute_disparity(img, img, d, "img"); }, "image width");
  expect_throw_naming([&] { block_matching(img, img, 16, 0, BlockCost::kSad, "img"); }, "window");
  EXPECT_NO_THROW(validate_disparity_config(DisparityConfig{}, "x"));
}

TEST(StereoValidation, BoardsGroundTruthAndCounts) {
  using namespace cropsight::stereo;
  Checkerboard b;
  b.cols = b.rows = 2;
  expect_throw_naming([&] { b.validate("board"); }, "inner corners");
  b = Checkerboard{};
  b.square_size = std::numeric_limits<double>::infinity();
  expect_throw_naming([&] { b.validate("board"); }, "square size");
  const DisparityImage est(4, 4, 1.0f), none(4, 4, std::numeric_limits<float>::quiet_NaN());
  expect_throw_naming([&] { bad_pixels(est, none, "gt"); }, "no valid pixel");
  cropsight::testing::TempDir tmp;
  cv::imwrite((tmp / "d16.png").string(), cv::Mat(4, 4, CV_16U, cv::Scalar(300)));
  expect_throw_naming([&] { read_disparity(tmp / "d16.png", 4, 8); }, "16-bit");
  EXPECT_NO_THROW(read_disparity(tmp / "d16.png", 256, 16));
  expect_throw_naming([&] { read_gray(tmp / "d16.png"); }, "16-bit");
  expect_throw_naming([&] { cropsight::sim::write_seedling_dataset(tmp / "s", {}, 2000000000, 1, 0); }, "pair count");
  EXPECT_FALSE(fs::exists(tmp / "s"));
}
