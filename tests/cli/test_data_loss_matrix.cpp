// The data-loss matrix: every command that writes, with its output aimed at what it must never
// touch. A cell is one (command, aim, --force or not); it passes when the command exits 2 with one
// line on stderr that starts "cropsight: " and names the output as given, and every file of the
// cell (the user's files, the inputs, the shared inputs they link to) is byte-identical afterwards:
// no file created, removed or changed, not even a temporary.
//
// The aims: the output is the command's main input, lies inside it, contains it (the folder that
// holds the inputs), is `.` while the working folder holds a user's files, and is a folder of a
// user's files (notes.md and sub/data.csv). Each with and without --force: --force only ever
// replaces an earlier cropsight output (io/output.hpp), so it must change none of these answers.
// One ctest test per command, so that `ctest -j2` spreads the CLI starts over both cores.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_inputs.hpp"
#include "testing/testing.hpp"

namespace data_loss_matrix {
namespace fs = std::filesystem;
using cropsight::testing::CommandResult;
using cropsight::testing::run_cli;
using cropsight::testing::snapshot;

enum class Out { File, Folder };

struct Row {
  std::string name;   ///< the ctest name's suffix
  std::string args;   ///< {c} = the cell folder, {out} = the output under test
  std::string input;  ///< the main input, relative to the cell ("" = the command reads no file)
  Out kind;
  std::string ext;  ///< a file output's extension, so that the name itself is never the problem
};

// gtest prints a failing row by this, not as bytes.
void PrintTo(const Row& row, std::ostream* os) { *os << row.name; }

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
    s.replace(at, from.size(), to);
  return s;
}

const std::vector<Row>& rows() {
  const std::string seq_rgbd =
      "--color {c}/seq/color/000000.png --depth {c}/seq/depth/000000.png --camera "
      "{c}/seq/camera.yaml --detections {c}/roi.json";
  const std::string pair = "--left {c}/sd/pair_000/left.png --right {c}/sd/pair_000/right.png --calib {c}/sd/rig.yaml";
  static const std::vector<Row> r = {
    {"detect_potato_data", "detect potato --data {c}/seq --out {out}", "seq", Out::Folder, ""},
    {"detect_potato_images", "detect potato --images {c}/images --out {out}", "images", Out::Folder, ""},
    {"detect_potato_overlay", "detect potato --images {c}/images --out {c}/new --overlay {out}", "images", Out::Folder,
     ""},
    {"detect_objects", "detect objects --model {c}/det.onnx --images {c}/images --out {out}", "images", Out::Folder,
     ""},
    {"detect_broccoli", "detect broccoli --data {c}/seq --model {c}/broccoli.json --out {out} --quiet", "seq",
     Out::File, ".jsonl"},
    {"detect_broccoli_masks",
     "detect broccoli --data {c}/seq --model {c}/broccoli.json --out {c}/d.jsonl --masks {out} --quiet", "seq",
     Out::Folder, ""},
    {"detect_broccoli_overlay",
     "detect broccoli --data {c}/seq --model {c}/broccoli.json --out {c}/d.jsonl --overlay {out} --quiet", "seq",
     Out::Folder, ""},
    {"detect_objects_overlay", "detect objects --model {c}/det.onnx --images {c}/images --out {c}/new --overlay {out}",
     "images", Out::Folder, ""},
    {"detect_broccoli_map",
     "detect broccoli --data {c}/seq --model {c}/broccoli.json --out {c}/d.jsonl --track --map {out} --quiet", "seq",
     Out::File, ".csv"},
    // Commands that read single files aim at one of them: a new file beside an input is no loss.
    {"detect_grape", "detect grape " + seq_rgbd + " --segmenter {c}/grape.json --threads 1 --out {out}",
     "seq/camera.yaml", Out::Folder, ""},
    {"detect_grape_overlay",
     "detect grape " + seq_rgbd + " --segmenter {c}/grape.json --threads 1 --out {c}/g --overlay {out}",
     "seq/camera.yaml", Out::Folder, ""},
    {"roi_cloud", "roi-cloud " + seq_rgbd + " --out {out}", "roi.json", Out::Folder, ""},
    {"detect_seedling", "detect seedling " + pair + " --out {out}", "sd/rig.yaml", Out::File, ".json"},
    {"detect_seedling_mask", "detect seedling " + pair + " --mask {out}", "sd/pair_000/left.png", Out::File, ".png"},
    {"stereo_disparity", "stereo disparity " + pair + " --max-disp 64 --out {out}", "sd/rig.yaml", Out::File, ".png"},
    {"stereo_disparity_preview", "stereo disparity " + pair + " --max-disp 64 --out {c}/d.png --preview {out}",
     "sd/rig.yaml", Out::File, ".png"},
    {"stereo_calibrate", "stereo calibrate --images {c}/sd --out {out}", "sd", Out::File, ".yaml"},
    {"import", "import --depth {c}/seq/depth --color {c}/seq/color --camera {c}/seq/camera.yaml --out {out}",
     "seq/depth", Out::Folder, ""},
    {"import_recorder",
     "import --depth {c}/rec/depth --color {c}/rec/color --camera {c}/rec/depth_info.yaml --color-camera "
     "{c}/rec/color_info.yaml --extrinsics {c}/rec/extrinsics.yaml --poses {c}/rec/poses.csv --out {out}",
     "rec/color", Out::Folder, ""},
    {"export", "export --data {c}/seq --frame 0 --out {out}", "seq", Out::File, ".pcd"},
    {"render", "render --data {c}/seq --frame 0 --out {out}", "seq", Out::File, ".png"},
    {"report", "report --data {c}/seq --out {out} --frames 1", "seq", Out::File, ".html"},
    // Every cell is a refusal, checked before any section is read: a grape folder is enough.
    {"report_demo", "report demo --grape {c}/clouds --out {out}", "clouds", Out::File, ".html"},
    {"harvest_potato", "harvest potato --data {c}/seq --out {out}", "seq", Out::File, ".jsonl"},
    {"segment_grape", "segment grape --model {c}/grape.json --clouds {c}/clouds/points/c0.txt --out {out} --threads 1",
     "clouds/points/c0.txt", Out::File, ".txt"},
    {"segment_grape_folder", "segment grape --model {c}/grape.json --clouds {c}/clouds --out {out} --threads 1 --quiet",
     "clouds", Out::Folder, ""},
    {"train_grape",
     "train grape --clouds {c}/clouds --model gbdt --out {out} --set gbdt.rounds=2 --set points_per_cloud=100 "
     "--threads 1",
     "clouds", Out::File, ".json"},
    {"train_broccoli", "train broccoli --data {c}/seq --out {out} --quiet", "seq", Out::File, ".json"},
    {"train_detector",
     "train detector --coco {c}/coco.json --images {c}/images --out {out} --epochs 1 --input-size 64x64", "images",
     Out::File, ".pt"},
    {"export_detector", "export-detector --model {c}/det.pt --out {out}", "det.pt", Out::File, ".onnx"},
    {"calibrate_detector",
     "tune-mask-thresholds --model {c}/det.pt --coco {c}/coco.json --images {c}/images --classes bunch,peduncle "
     "--out {out}",
     "images", Out::File, ".pt"},
    {"simulate_broccoli", "simulate broccoli --frames 1 --out {out}", "", Out::Folder, ""},
    {"simulate_potato", "simulate potato --frames 1 --out {out}", "", Out::Folder, ""},
    {"simulate_seedling", "simulate seedling --pairs 1 --calib-pairs 0 --quiet --out {out}", "", Out::Folder, ""},
    {"simulate_grape", "simulate grape --out {out}", "", Out::Folder, ""},
#if CROPSIGHT_HAS_ROS
    {"export_bag", "export --data {c}/seq --out {out}", "seq", Out::File, ".bag"},
    {"import_bag", "import --data {c}/s.bag --out {out}", "s.bag", Out::Folder, ""},
#endif
  };
  return r;
}

struct Aim {
  std::string name;
  std::string out;              ///< relative to the cell ("." for the working folder)
  bool in_user_folder = false;  ///< run from the user's folder
};

// The aims that apply to a row.
std::vector<Aim> aims_of(const Row& row) {
  std::vector<Aim> a;
  if (!row.input.empty()) {
    a.push_back({"out-is-input", row.input});
    a.push_back({"out-inside-input", row.input + "/new" + row.ext});
    a.push_back({"input-inside-out", "."});
  }
  a.push_back({"out-is-dot", ".", true});
  a.push_back({"out-is-a-user-folder", "user"});
  return a;
}

class DataLossMatrix : public cropsight::testing::CliInputsSuite<Row> {
 protected:
  // A cell: the main input copied (a command aimed at it must find it there), every other input
  // linked, and the user's folder.
  static void make_user_cell(const fs::path& cell, const std::string& input) {
    make_cell(cell, input);
    fs::create_directories(cell / "user/sub");
    cropsight::testing::write_text(cell / "user/notes.md", "my field notes\n");
    cropsight::testing::write_text(cell / "user/sub/data.csv", "plot,yield\n1,42\n");
  }
};

TEST_P(DataLossMatrix, Cells) {
  ASSERT_TRUE(ok()) << "fixture simulation failed";
  const Row& row = GetParam();
  const auto shared_before = snapshot(inputs());
  const fs::path start = fs::current_path();
  int cells = 0, failed = 0;
  std::string failures;
  for (const Aim& aim : aims_of(row)) {
    for (bool force : {false, true}) {
      cropsight::testing::TempDir t;
      const fs::path cell = t / "cell";
      make_user_cell(cell, row.input);
      const std::string out = aim.in_user_folder ? "." : (cell / aim.out).lexically_normal().string();
      std::string args = replace_all(replace_all(row.args, "{out}", out), "{c}", cell.string());
      if (force) args += " --force";
      const auto before = snapshot(cell);
      if (aim.in_user_folder) fs::current_path(cell / "user");
      const CommandResult r = run_cli(args);
      fs::current_path(start);
      const auto after = snapshot(cell);
      ++cells;
      std::string why;
      if (r.exit_code != 2) why += " exit " + std::to_string(r.exit_code) + ";";
      const auto lines = std::count(r.err.begin(), r.err.end(), '\n');
      if (lines != 1) why += " stderr has " + std::to_string(lines) + " lines;";
      if (r.err.rfind("cropsight: ", 0) != 0) why += " no 'cropsight: ' prefix;";
      const std::string named = aim.in_user_folder ? "cropsight: .:" : out;
      if (r.err.find(named) == std::string::npos) why += " does not name the output;";
      if (before != after) why += " THE CELL CHANGED;";
      if (!why.empty()) {
        ++failed;
        failures += "  " + aim.name + (force ? " --force" : "") + ":" + why +
                    " stderr: " + replace_all(r.err.substr(0, r.err.find('\n')), cell.string(), "CELL") + "\n";
      }
    }
  }
  EXPECT_EQ(snapshot(inputs()), shared_before) << "the shared inputs changed";
  std::printf("data-loss matrix: %s %d cells, %d pass, %d fail\n", row.name.c_str(), cells, cells - failed, failed);
  EXPECT_EQ(failed, 0) << row.name << ":\n" << failures;
}

INSTANTIATE_TEST_SUITE_P(Commands, DataLossMatrix, ::testing::ValuesIn(rows()),
                         [](const ::testing::TestParamInfo<Row>& p) { return p.param.name; });

// The other half of the rule: a folder cropsight wrote is replaced with --force, and refused
// without it; a file the user added to it makes --force refuse too.
TEST(DataLoss, ForceReplacesOnlyAnEarlierCropsightOutput) {
  cropsight::testing::TempDir t;
  const std::string out = cropsight::testing::shell_quoted(t / "sim");
  ASSERT_EQ(run_cli("simulate potato --frames 1 --quiet --out " + out).exit_code, 0);
  const CommandResult again = run_cli("simulate potato --frames 1 --quiet --out " + out);
  EXPECT_EQ(again.exit_code, 2);
  EXPECT_NE(again.err.find("--force"), std::string::npos) << again.err;
  EXPECT_EQ(run_cli("simulate potato --frames 1 --quiet --seed 2 --out " + out + " --force").exit_code, 0);
  cropsight::testing::write_text(t / "sim/notes.md", "mine\n");
  const CommandResult refused = run_cli("simulate potato --frames 1 --quiet --out " + out + " --force");
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("notes.md"), std::string::npos) << refused.err;
  EXPECT_TRUE(fs::exists(t / "sim/notes.md"));
}

// An unwritable --out is refused before the first frame is read: no progress line, one error line.
TEST(DataLoss, UnwritableOutputFailsBeforeTheWork) {
  cropsight::testing::TempDir t;
  ASSERT_EQ(
      run_cli("simulate broccoli --frames 2 --quiet --out " + cropsight::testing::shell_quoted(t / "seq")).exit_code,
      0);
  const CommandResult r =
      run_cli("detect broccoli --data " + cropsight::testing::shell_quoted(t / "seq") + " --model " +
              cropsight::testing::shell_quoted(cropsight::testing::source_dir() / "models/broccoli-oes-uk.json") +
              " --out /proc/cropsight-x/det.jsonl");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("/proc/cropsight-x/det.jsonl"), std::string::npos) << r.err;
}

}  // namespace data_loss_matrix
