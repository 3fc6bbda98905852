// Import round trips: a simulated pass written in RealSense and Kinect recorder layouts (JPEG
// colour of another resolution with known extrinsics, camera_info YAMLs, timestamped or numbered
// names, a pose file) imports to the same depth, the same colour (registered, within a stated
// tolerance), the same timestamps and poses. And the new inputs' bad cases: one line, exit 2,
// nothing written.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli/recorder_layouts.hpp"
#include "cropsight/io/files.hpp"
#include "testing/testing.hpp"

namespace cropsight::testing {
namespace {

namespace fs = std::filesystem;

class ImportLayouts : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir;
    const CommandResult r = run_cli("simulate broccoli --frames 4 --out " + shell_quoted(*dir_ / "sim"));
    ok_ = r.exit_code == 0;
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static fs::path sim() { return *dir_ / "sim"; }
  static fs::path dir() { return dir_->path(); }
  static inline TempDir* dir_ = nullptr;
  static inline bool ok_ = false;

  static std::string replace(std::string s, const fs::path& from, const fs::path& to) {
    const std::string a = shell_quoted(from), b = shell_quoted(to);
    return s.replace(s.find(a), a.size(), b);
  }

  static std::string import_args(const RecorderLayout& l, const fs::path& out) {
    return "import --depth " + shell_quoted(l.depth_dir) + " --color " + shell_quoted(l.color_dir) + " --camera " +
           shell_quoted(l.depth_info) + " --color-camera " + shell_quoted(l.color_info) + " --extrinsics " +
           shell_quoted(l.extrinsics) + " --poses " + shell_quoted(l.poses) + " " + l.extra_args + " --out " +
           shell_quoted(out);
  }

  struct ColourMatch {
    double coverage = 0;    // share of the valid depth pixels that got a colour
    double mean_error = 0;  // mean |registered - simulated| over those, 8-bit levels per channel
  };

  static ColourMatch colour_match(const io::SequenceReader& truth, const io::SequenceReader& back) {
    long coloured = 0, valid = 0;
    double abs_error = 0;
    for (int i = 0; i < truth.size(); ++i) {
      const RgbdFrame a = truth.read(i), b = back.read(i);
      for (std::size_t k = 0; k < a.depth.data.size(); ++k) {
        if (a.depth.data[k] == 0) continue;
        ++valid;
        const Rgb8 x = a.color.data[k], y = b.color.data[k];
        if (y == Rgb8{}) continue;  // hidden from the colour camera, or outside its image
        ++coloured;
        abs_error += (std::abs(x.r - y.r) + std::abs(x.g - y.g) + std::abs(x.b - y.b)) / 3.0;
      }
    }
    return {double(coloured) / double(valid), abs_error / double(coloured)};
  }

  // Imports `recorder`'s layout of the simulated pass and compares the sequence with the pass.
  RecorderLayout round_trip(Recorder recorder, const std::string& name, ColourMatch& match) {
    const io::SequenceReader truth(sim());
    const RecorderLayout l = write_recorder_layout(truth, dir() / name, recorder);
    const fs::path out = dir() / (name + "-imported");
    const CommandResult r = run_cli(import_args(l, out) + " --json");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    if (r.exit_code != 0) return l;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_TRUE(j["color_registered"].get<bool>());
    EXPECT_EQ(j["poses"], recorder == Recorder::RealSense ? "csv" : "tum");
    const io::SequenceReader back(out);
    EXPECT_EQ(back.size(), truth.size());
    for (int i = 0; i < std::min(truth.size(), back.size()); ++i) {
      const RgbdFrame a = truth.read(i), b = back.read(i);
      EXPECT_EQ(b.depth, a.depth) << name << " frame " << i;
      EXPECT_NEAR(b.timestamp, a.timestamp, 1e-6) << name << " frame " << i;
      EXPECT_TRUE(b.camera_position.has_value());
      if (b.camera_position) {
        EXPECT_LT((*b.camera_position - *a.camera_position).norm(), 1e-6) << name << " " << i;
      }
    }
    match = colour_match(truth, back);
    std::printf("import round trip %s: colour on %.4f of the valid depth pixels, mean |error| %.2f levels\n",
                name.c_str(), match.coverage, match.mean_error);
    // Measured 0.987 / 0.953 and 4.0 / 3.8 levels: JPEG at quality 95, and the colour camera's
    // pixels painted from the nearest depth point by the layout writer.
    EXPECT_GT(match.coverage, 0.93) << name;
    EXPECT_LT(match.mean_error, 6.0) << name;
    return l;
  }
};

// The colour comparison can fail: the same files registered with the colour camera put at the
// depth camera's place (identity extrinsics) give a clearly larger error.
TEST_F(ImportLayouts, RealSenseLayout) {
  ASSERT_TRUE(ok_) << "simulation failed";
  ColourMatch right, wrong;
  RecorderLayout l = round_trip(Recorder::RealSense, "realsense", right);
  write_text(dir() / "identity.yaml",
             "depth_to_color:\n  rotation: [1, 0, 0, 0, 1, 0, 0, 0, 1]\n  translation: [0, 0, 0]\n");
  l.extrinsics = dir() / "identity.yaml";
  ASSERT_EQ(run_cli(import_args(l, dir() / "identity-imported")).exit_code, 0);
  wrong = colour_match(io::SequenceReader(sim()), io::SequenceReader(dir() / "identity-imported"));
  std::printf("import round trip realsense with identity extrinsics: mean |error| %.2f levels\n", wrong.mean_error);
  EXPECT_GT(wrong.mean_error, 2.0 * right.mean_error);
}

TEST_F(ImportLayouts, KinectLayout) {
  ASSERT_TRUE(ok_) << "simulation failed";
  ColourMatch m;
  round_trip(Recorder::Kinect, "kinect", m);
}
// Each bad input the issue names: one line naming the file and the problem, exit 2, no output and
// no temporary left beside it.
TEST_F(ImportLayouts, BadInputsAreOneLineAndWriteNothing) {
  ASSERT_TRUE(ok_) << "simulation failed";
  const RecorderLayout good = write_recorder_layout(io::SequenceReader(sim()), dir() / "bad-base", Recorder::RealSense);
  const auto expect_refused = [&](const std::string& args, const fs::path& named, const std::string& problem) {
    const fs::path out = dir() / "bad-out";
    const CommandResult r = run_cli(args + " --out " + shell_quoted(out));
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(named.string()), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(problem), std::string::npos) << r.err;
    for (const auto& e : fs::directory_iterator(dir()))
      EXPECT_EQ(e.path().filename().string().find("bad-out"), std::string::npos) << e.path();
  };
  const std::string base = import_args(good, dir() / "unused");
  const std::string without_out = base.substr(0, base.find(" --out "));
  // A camera_info with a zero focal length.
  const std::string info = io::read_file(good.depth_info);
  const std::size_t k = info.find("K: [") + 4;
  write_text(dir() / "zero_focal.yaml", info.substr(0, k) + "0" + info.substr(info.find(',', k)));
  expect_refused(replace(without_out, good.depth_info, dir() / "zero_focal.yaml"), dir() / "zero_focal.yaml",
                 "focal lengths fx, fy must be finite and positive");
  // Poses with a NaN time, and with time going back.
  write_text(dir() / "nan.csv", "timestamp,x,y,z\n1596203844.0,0,0,1\nnan,0.1,0,1\n");
  expect_refused(replace(without_out, good.poses, dir() / "nan.csv"), dir() / "nan.csv",
                 "line 3: timestamp must be a finite number, got 'nan'");
  write_text(dir() / "back.csv", "timestamp,x,y,z\n1596203844.2,0,0,1\n1596203844.1,0.1,0,1\n");
  expect_refused(replace(without_out, good.poses, dir() / "back.csv"), dir() / "back.csv", "does not increase");
  // Colour of another size without the colour camera and extrinsics to register it.
  const std::string plain = "import --depth " + shell_quoted(good.depth_dir) + " --color " +
                            shell_quoted(good.color_dir) + " --camera " + shell_quoted(good.depth_info);
  expect_refused(plain, good.color_dir, "colour of another size is registered to depth with --color-camera and");
  // An unknown camera file names the accepted formats.
  write_text(dir() / "intrinsics.yaml", "focal: 365\n");
  expect_refused(replace(without_out, good.depth_info, dir() / "intrinsics.yaml"), dir() / "intrinsics.yaml",
                 "ROS camera_info YAML");
}

// The frames' times reach every output that carries time: harvest potato's lines, and a bag
// exported from the imported sequence (which lasts as long as the recording).
TEST_F(ImportLayouts, TimestampsReachHarvestAndBag) {
  ASSERT_TRUE(ok_) << "simulation failed";
  const io::SequenceReader truth(sim());
  const RecorderLayout l = write_recorder_layout(truth, dir() / "timed", Recorder::RealSense);
  std::string args = import_args(l, dir() / "timed-seq");
  args.replace(args.find(" --poses "), std::string(" --poses " + shell_quoted(l.poses)).size(), "");
  ASSERT_EQ(run_cli(args).exit_code, 0);
  EXPECT_TRUE(fs::exists(dir() / "timed-seq" / "timestamps.csv"));  // no poses: the times' own file
  CommandResult r = run_cli("info --json --data " + shell_quoted(dir() / "timed-seq"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NEAR(nlohmann::json::parse(r.out)["duration_s"].get<double>(), truth.read(truth.size() - 1).timestamp, 1e-6);
  r = run_cli("harvest potato --data " + shell_quoted(dir() / "timed-seq") + " --out " +
              shell_quoted(dir() / "h.jsonl"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream lines(dir() / "h.jsonl");
  int frame = 0;
  for (std::string line; std::getline(lines, line); ++frame)
    EXPECT_NEAR(nlohmann::json::parse(line)["timestamp"].get<double>(), truth.read(frame).timestamp, 1e-6);
  EXPECT_EQ(frame, truth.size());
#if CROPSIGHT_HAS_ROS
  r = run_cli("export --data " + shell_quoted(dir() / "timed-seq") + " --out " + shell_quoted(dir() / "t.bag"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_cli("import --data " + shell_quoted(dir() / "t.bag") + " --out " + shell_quoted(dir() / "from-bag"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const io::SequenceReader back(dir() / "from-bag");
  ASSERT_EQ(back.size(), truth.size());
  for (int i = 0; i < truth.size(); ++i) EXPECT_NEAR(back.read(i).timestamp, truth.read(i).timestamp, 1e-6);
#endif
}

// import --pcd keeps the PCDs' label field as labels/.
TEST_F(ImportLayouts, PcdLabelsKept) {
  ASSERT_TRUE(ok_) << "simulation failed";
  fs::create_directories(dir() / "pcd");
  for (int i = 0; i < 2; ++i)
    ASSERT_EQ(run_cli("export --data " + shell_quoted(sim()) + " --frame " + std::to_string(i) + " --out " +
                      shell_quoted(dir() / "pcd" / ("cloud_" + std::to_string(i) + ".pcd")))
                  .exit_code,
              0);
  const CommandResult r = run_cli("import --pcd " + shell_quoted(dir() / "pcd") + " --camera " +
                                  shell_quoted(sim() / "camera.yaml") + " --out " + shell_quoted(dir() / "from-pcd"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("labels"), std::string::npos) << r.out;
  const io::SequenceReader truth(sim()), back(dir() / "from-pcd");
  ASSERT_TRUE(back.info().has_labels);
  for (int i = 0; i < 2; ++i) EXPECT_EQ(back.read(i).labels, truth.read(i).labels) << "frame " << i;
}

}  // namespace
}  // namespace cropsight::testing

namespace cropsight::testing {
namespace {

// --poses with GNSS fixes (a lat/lon CSV here; NMEA reads the same way): the sequence gets the
// fixes as field-frame positions and a geo_origin.yaml, so that batch maps are geo-referenced.
TEST_F(ImportLayouts, GnssPosesGeoReferenceTheSequence) {
  ASSERT_TRUE(ok_) << "simulation failed";
  const io::SequenceReader truth(sim());
  const RecorderLayout l = write_recorder_layout(truth, dir() / "gnss", Recorder::RealSense);
  // The recorder's pose times, each as a fix 0.00001° further north (about 1.11 m).
  std::ifstream poses(l.poses);
  std::string line, fixes = "timestamp,lat,lon\n";
  std::getline(poses, line);  // header: timestamp first
  for (int k = 0; std::getline(poses, line); ++k) {
    char lat[32];
    std::snprintf(lat, sizeof lat, "%.5f", 52.2 + 1e-5 * k);
    fixes += line.substr(0, line.find(',')) + "," + lat + ",0.12\n";
  }
  write_text(dir() / "gnss.csv", fixes);
  std::string args = import_args(l, dir() / "gnss-seq");
  args = replace(args, l.poses, dir() / "gnss.csv");
  const CommandResult r = run_cli(args + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["poses"], "gnss");
  ASSERT_TRUE(fs::exists(dir() / "gnss-seq" / "geo_origin.yaml"));
  const io::SequenceReader back(dir() / "gnss-seq");
  ASSERT_EQ(back.poses().size(), std::size_t(truth.size()));
  for (std::size_t i = 1; i < back.poses().size(); ++i)  // driving north: x grows, y stays
    EXPECT_GT(back.poses()[i].position.x(), back.poses()[i - 1].position.x());
}

}  // namespace
}  // namespace cropsight::testing
