// The bad-input matrix (deliverable 3): every CLI command against each class of bad
// input its inputs can have. A cell is one (command, input, class); it passes when the command
// exits 2, prints exactly one line on stderr that starts "cropsight: " and names the broken file
// (or the --set key, or the output folder), and leaves the cell's folder exactly as it was (no
// file created, removed or changed: no output, not even a partial one or a temporary).
//
// Each cell runs in a fresh folder: the input it breaks is copied there, the others are symbolic
// links to one shared set made once per suite. One ctest test per command (TEST_P), so that
// `ctest -j2` spreads the ~250 CLI starts over both cores. docs/reliability.md has the counts.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cli_inputs.hpp"
#include "cropsight/io/grape_text.hpp"
#include "pipeline/grape/grape_test_clouds.hpp"
#include "testing/testing.hpp"

namespace {
namespace fs = std::filesystem;
using cropsight::testing::CommandResult;
using cropsight::testing::run_cli;
using cropsight::testing::shell_quoted;

enum class Bad {
  Missing,
  Empty,
  Truncated,
  Directory,
  WrongDepth,
  WrongSize,
  NaN,
  Inf,
  WrongType,
  UnknownKey,
  OutOfRange,
  Unwritable
};
const char* name_of(Bad b) {
  switch (b) {
    case Bad::Missing:
      return "missing";
    case Bad::Empty:
      return "empty";
    case Bad::Truncated:
      return "truncated";
    case Bad::Directory:
      return "directory";
    case Bad::WrongDepth:
      return "wrong-depth";
    case Bad::WrongSize:
      return "wrong-size";
    case Bad::NaN:
      return "nan";
    case Bad::Inf:
      return "inf";
    case Bad::WrongType:
      return "wrong-type";
    case Bad::UnknownKey:
      return "unknown-key";
    case Bad::OutOfRange:
      return "out-of-range";
    case Bad::Unwritable:
      return "unwritable-output";
  }
  return "?";
}

// What an input is decides which classes of bad input it can have and how each is made.
enum class Kind { Yaml, Json, Csv, Png, Cloud, Xml, Binary, Set, Output };
std::vector<Bad> classes_of(Kind k) {
  using B = Bad;
  switch (k) {
    case Kind::Yaml:
      return {B::Missing, B::Empty,     B::Truncated,  B::Directory, B::NaN,
              B::Inf,     B::WrongType, B::UnknownKey, B::OutOfRange};
    // JSON files: model files and truth carry extra fields by design (docs/formats.md), so no
    // unknown-key cell; the YAML configs and --set carry that class.
    case Kind::Json:
      return {B::Missing, B::Empty, B::Truncated, B::Directory, B::NaN, B::Inf, B::WrongType, B::OutOfRange};
    case Kind::Csv:  // poses.csv is optional: no missing cell
      return {B::Empty, B::Truncated, B::Directory, B::NaN, B::Inf, B::WrongType, B::OutOfRange};
    case Kind::Png:
      return {B::Missing, B::Empty, B::Truncated, B::Directory, B::WrongDepth, B::WrongSize};
    case Kind::Cloud:
      return {B::Missing, B::Empty, B::Truncated, B::Directory, B::NaN, B::Inf, B::WrongType, B::OutOfRange};
    case Kind::Xml:
      return {B::Missing, B::Empty, B::Truncated, B::Directory, B::NaN, B::WrongType, B::OutOfRange};
    case Kind::Binary:
      return {B::Missing, B::Empty, B::Truncated, B::Directory};
    case Kind::Set:
      return {B::NaN, B::Inf, B::WrongType, B::UnknownKey, B::OutOfRange};
    case Kind::Output:
      return {B::Unwritable};
  }
  return {};
}

/// One input of a command. `path` is relative to the cell folder ("seq/camera.yaml"); `key` is
/// the field a value class edits (YAML: dotted path; JSON: pointer; CSV: "row,column"; XML: a tag;
/// --set: the key) and `range` the out-of-range value, as the file's own text.
struct Input {
  std::string path;
  Kind kind;
  std::string key;
  std::string range;
  /// Classes that are no bad input for this input (each says why where it is declared).
  std::vector<Bad> na = {};
};

struct Row {
  std::string name;  ///< the ctest name's suffix
  std::string args;  ///< {c} = the cell folder; outputs go under {c}/out/
  std::vector<Input> inputs;
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
void spit(const fs::path& p, const std::string& text) { cropsight::testing::write_text(p, text); }

// The raw text that stands for a value class in each format.
std::string raw_value(Kind k, Bad b, const Input& in) {
  const bool yaml = k == Kind::Yaml || k == Kind::Set;
  switch (b) {
    case Bad::NaN:
      return yaml ? ".nan" : k == Kind::Json ? "NaN" : "nan";
    case Bad::Inf:
      return yaml ? ".inf" : k == Kind::Json ? "Infinity" : "inf";
    case Bad::WrongType:
      return yaml ? "[1, 2]" : k == Kind::Json ? "\"text\"" : "abc";
    case Bad::OutOfRange:
      return in.range;
    default:
      return "";
  }
}

// YAML and JSON: the value at `key` becomes a placeholder that the writer leaves unquoted (or
// quotes, in JSON), then the placeholder becomes the raw text (NaN is no JSON a library writes).
std::string edit_yaml(const std::string& text, const std::string& key, const std::string& raw) {
  YAML::Node root = YAML::Load(text);
  YAML::Node node = root;
  std::stringstream parts(key);
  std::vector<std::string> path;
  for (std::string p; std::getline(parts, p, '.');) path.push_back(p);
  std::vector<YAML::Node> chain{root};
  for (size_t i = 0; i + 1 < path.size(); ++i) chain.push_back(chain.back()[path[i]]);
  chain.back()[path.back()] = "XXVALXX";
  YAML::Emitter e;
  e << root;
  std::string out = e.c_str();
  const size_t at = out.find("XXVALXX");
  EXPECT_NE(at, std::string::npos) << key;
  return out.replace(at, 7, raw) + "\n";
}
std::string edit_json(const std::string& text, const std::string& key, const std::string& raw) {
  auto j = nlohmann::json::parse(text);
  EXPECT_TRUE(j.contains(nlohmann::json::json_pointer(key))) << key;
  j[nlohmann::json::json_pointer(key)] = "XXVALXX";
  std::string out = j.dump(1);
  const size_t at = out.find("\"XXVALXX\"");
  return out.replace(at, 9, raw);
}
// CSV: `key` "row,column" (row 0 = header).
std::string edit_csv(const std::string& text, const std::string& key, const std::string& raw) {
  const int row = std::stoi(key.substr(0, key.find(','))), col = std::stoi(key.substr(key.find(',') + 1));
  std::stringstream in(text);
  std::string out, line;
  for (int r = 0; std::getline(in, line); ++r) {
    if (r == row) {
      std::vector<std::string> f;
      std::stringstream ls(line);
      for (std::string x; std::getline(ls, x, ',');) f.push_back(x);
      f.at(col) = raw;
      line.clear();
      for (size_t i = 0; i < f.size(); ++i) line += (i ? "," : "") + f[i];
    }
    out += line + "\n";
  }
  return out;
}
// Text clouds: column `key` of the first point line.
std::string edit_cloud(const std::string& text, const std::string& key, const std::string& raw) {
  std::stringstream in(text);
  std::string out, line;
  bool done = false;
  while (std::getline(in, line)) {
    if (!done && !line.empty() && (std::isdigit(static_cast<unsigned char>(line[0])) || line[0] == '-')) {
      std::vector<std::string> f;
      std::stringstream ls(line);
      for (std::string x; ls >> x;) f.push_back(x);
      f.at(std::stoul(key)) = raw;
      line.clear();
      for (size_t i = 0; i < f.size(); ++i) line += (i ? " " : "") + f[i];
      done = true;
    }
    out += line + "\n";
  }
  return out;
}
std::string edit_xml(const std::string& text, const std::string& tag, const std::string& raw) {
  return std::regex_replace(text, std::regex("<" + tag + ">[^<]*</" + tag + ">"),
                            "<" + tag + ">" + raw + "</" + tag + ">", std::regex_constants::format_first_only);
}

// Breaks `p` (a copy, never the shared original) as `b` says.
void make_bad(const fs::path& p, const Input& in, Bad b) {
  const std::string text = fs::is_regular_file(p) ? slurp(p) : "";
  switch (b) {
    case Bad::Missing:
      fs::remove_all(p);
      return;
    case Bad::Empty:
      spit(p, "");
      return;
    case Bad::Truncated:
      spit(p, text.substr(0, text.size() / 2));
      return;
    case Bad::Directory:
      fs::remove_all(p);
      fs::create_directories(p);
      return;
    case Bad::WrongDepth:
    case Bad::WrongSize: {
      const cv::Mat m = cv::imread(p.string(), cv::IMREAD_UNCHANGED);
      ASSERT_FALSE(m.empty()) << p;
      cv::Mat bad;
      if (b == Bad::WrongSize)
        bad = cv::Mat(m.rows / 2 + 1, m.cols / 2 + 3, m.type(), cv::Scalar::all(100));
      else  // 16-bit depth becomes 8-bit, 8-bit colour becomes 16-bit
        bad = cv::Mat(m.rows, m.cols, m.depth() == CV_16U ? CV_8UC1 : CV_16UC1, cv::Scalar::all(100));
      cv::imwrite(p.string(), bad);
      return;
    }
    default:
      break;
  }
  const std::string raw = raw_value(in.kind, b, in);
  switch (in.kind) {
    case Kind::Yaml:
      spit(p, b == Bad::UnknownKey ? text + "\nno_such_key_xyz: 1\n" : edit_yaml(text, in.key, raw));
      return;
    case Kind::Json:
      spit(p, edit_json(text, in.key, raw));
      return;
    case Kind::Csv:
      spit(p, edit_csv(text, in.key, raw));
      return;
    case Kind::Cloud:
      spit(p, edit_cloud(text, in.key, raw));
      return;
    case Kind::Xml:
      spit(p, edit_xml(text, in.key, raw));
      return;
    default:
      FAIL() << "no " << name_of(b) << " for " << in.path;
  }
}

using cropsight::testing::snapshot;

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
    s.replace(at, from.size(), to);
  return s;
}

// The commands and what each reads. Sequence readers get the sequence's files; the rest their own.
const Input kCamera{"seq/camera.yaml", Kind::Yaml, "fx", "-5"};
const Input kDepth{"seq/depth/000000.png", Kind::Png, "", ""};
const Input kColor{"seq/color/000000.png", Kind::Png, "", ""};
const Input kLabels{"seq/labels/000000.png", Kind::Png, "", ""};
const Input kPoses{"seq/poses.csv", Kind::Csv, "1,0", "7"};  // frame 0's row says frame 7
// groundtruth.json is optional (docs/formats.md): a sequence without it is a robot's recording.
const Input kTruth{"seq/groundtruth.json", Kind::Json, "/instances/0/diameter_mm", "-5", {Bad::Missing}};
const Input kBroccoliModel{"broccoli.json", Kind::Json, "/config/depth.min_depth", "\"-5\""};
// bench broccoli times the presets' pipelines with the model's classifier only: it never reads
// the model's config, so a wrong value there is no input of it.
const Input kBroccoliModelBench{
    "broccoli.json", Kind::Json, "/config/depth.min_depth", "\"-5\"", {Bad::WrongType, Bad::OutOfRange}};
// A preset overrides the struct defaults key by key: an empty one, or one cut after a complete
// line, is a valid (shorter) preset.
const Input kPreset{"preset.yaml", Kind::Yaml, "depth.min_depth", "-5", {Bad::Empty, Bad::Truncated}};
// One cloud of a folder: a folder with one cloud fewer, or a sub-folder beside the clouds, is a
// valid data set (the readers take the *.txt files).
const Input kGrapeCloud{"clouds/points/c0.txt", Kind::Cloud, "9", "99", {Bad::Missing, Bad::Directory}};
const Input kGrapeModel{"grape.json", Kind::Json, "/learner/attributes/cropsight.num_class", "\"-3\""};
const Input kLeft{"sd/pair_000/left.png", Kind::Png, "", ""};
const Input kRig{"sd/rig.yaml", Kind::Yaml, "image_width", "-640"};
const Input kSeedTruth{"sd/pair_000/truth.json", Kind::Json, "/envelope/height_m", "-1"};
// Images named by COCO truth: the detectors take any size (they resize to the network input).
const Input kImage{"images/a.png", Kind::Png, "", "", {Bad::WrongSize}};
// One image of a folder to detect in: one image fewer, or a sub-folder beside the images (whatever
// its name), is a valid folder too (io::list_images takes the image files).
const Input kFolderImage{"images/a.png", Kind::Png, "", "", {Bad::WrongSize, Bad::Missing, Bad::Directory}};
const Input kOnnx{"det.onnx", Kind::Binary, "", ""};
const Input kPt{"det.pt", Kind::Binary, "", ""};
const Input kCocoGt{"coco.json", Kind::Json, "/annotations/0/bbox/2", "-20"};
const Input kRoiDet{"roi.json", Kind::Json, "/0/bbox/2", "-50"};
// Out of range: xmin beyond xmax. (A box partly outside <size> is accepted: VOC sets have them.)
// One annotation file fewer (or a sub-folder) in the folder is a valid set: images without truth.
const Input kVoc{"voc/a.xml", Kind::Xml, "xmin", "1000", {Bad::Missing, Bad::Directory}};
const Input kOut{"out", Kind::Output, "", ""};
// A ROS bag of the sequence (cropsight export --bag), in builds with ROS.
const Input kBag{"s.bag", Kind::Binary, "", ""};
// import's recorder inputs (cli/recorder_layouts.hpp, RealSense layout). A ROS camera_info carries
// keys cropsight does not use (R, P, roi, binning), so an unknown key is no bad input of it.
const Input kDepthInfo{"rec/depth_info.yaml", Kind::Yaml, "width", "-640", {Bad::UnknownKey}};
const Input kColorInfo{"rec/color_info.yaml", Kind::Yaml, "image_width", "-640", {Bad::UnknownKey}};
const Input kExtrinsics{"rec/extrinsics.yaml", Kind::Yaml, "depth_to_color.translation", "[0, 0]"};
// Out of range: the pose between frames 0 and 1 dated before frame 0's (time going back).
const Input kPoseCsv{"rec/poses.csv", Kind::Csv, "2,0", "1"};
// One colour image fewer (or a folder in its place) is a count mismatch named by its folder
// (test_import_layouts_cli.cpp); a JPEG holds 8 bits only.
const Input kRecColor{
    "rec/color/_Color_1596203844003.217.jpg", Kind::Png, "", "", {Bad::Missing, Bad::Directory, Bad::WrongDepth}};
Input set(const std::string& key, const std::string& range) { return {key, Kind::Set, key, range}; }

// A table, one row per command: long because the command list is.
const std::vector<Row>& rows() {
  static const std::vector<Row> r = {
    {"info", "info --data {c}/seq", {kCamera, kDepth, kColor, kLabels, kPoses, kTruth}},
    {"export", "export --data {c}/seq --frame 0 --out {c}/out/f.pcd", {kCamera, kDepth, kOut}},
    {"render", "render --data {c}/seq --frame 0 --out {c}/out/f.png --what labels", {kCamera, kDepth, kLabels, kOut}},
    {"report",
     "report --data {c}/seq --out {c}/out/r.html --frames 1 --model {c}/broccoli.json",
     {kCamera, kDepth, kBroccoliModel, kOut}},
    {"train_broccoli",
     "train broccoli --data {c}/seq --out {c}/out/m.json --quiet --config {c}/preset.yaml",
     {kCamera, kDepth, kLabels, kTruth, kPreset, set("depth.min_depth", "-5"), kOut}},
    {"detect_broccoli",
     "detect broccoli --data {c}/seq --model {c}/broccoli.json --out {c}/out/d.jsonl --quiet --track",
     {kCamera, kDepth, kPoses, kBroccoliModel, set("tracking.max_distance", "-5"), kOut}},
    {"eval_broccoli",
     "eval broccoli --data {c}/seq --model {c}/broccoli.json --quiet",
     {kCamera, kDepth, kLabels, kTruth, kBroccoliModel, set("depth.min_depth", "-5")}},
    {"bench_broccoli",
     "bench broccoli --data {c}/seq --model {c}/broccoli.json --frames 1 --pipelines oes",
     {kCamera, kDepth, kBroccoliModelBench}},
    {"detect_potato", "detect potato --data {c}/seq --out {c}/out/p", {kCamera, kDepth, kColor, kOut}},
    {"harvest_potato", "harvest potato --data {c}/seq --out {c}/out/h.jsonl", {kCamera, kDepth, kColor, kOut}},
    {"import",
     "import --depth {c}/seq/depth --color {c}/seq/color --camera {c}/seq/camera.yaml --out {c}/out/imp",
     {kCamera, kDepth, kColor, kOut}},
    {"import_recorder",
     "import --depth {c}/rec/depth --color {c}/rec/color --camera {c}/rec/depth_info.yaml --color-camera "
     "{c}/rec/color_info.yaml --extrinsics {c}/rec/extrinsics.yaml --poses {c}/rec/poses.csv --out {c}/out/imp",
     {kDepthInfo, kColorInfo, kExtrinsics, kPoseCsv, kRecColor, kOut}},
    {"simulate_broccoli", "simulate broccoli --frames 1 --out {c}/out/s", {set("camera.height_m", "-1"), kOut}},
    {"simulate_potato", "simulate potato --frames 1 --out {c}/out/s", {kOut}},
    {"simulate_seedling", "simulate seedling --pairs 1 --calib-pairs 0 --quiet --out {c}/out/s", {kOut}},
    {"simulate_grape", "simulate grape --out {c}/out/s", {set("berry_radius_min", "-1"), kOut}},
    {"segment_grape",
     "segment grape --model {c}/grape.json --clouds {c}/clouds/points/c0.txt --out {c}/out/s.txt --threads 1",
     {kGrapeCloud, kGrapeModel, kOut}},
    {"train_grape",
     "train grape --clouds {c}/clouds --model gbdt --out {c}/out/g.json --set gbdt.rounds=2 --set points_per_cloud=100 "
     "--threads 1",
     {kGrapeCloud, set("gbdt.rounds", "-2"), kOut}},
    {"eval_grape", "eval grape --clouds {c}/clouds --model {c}/grape.json --threads 1", {kGrapeCloud, kGrapeModel}},
    {"roi_cloud",
     "roi-cloud --color {c}/seq/color/000000.png --depth {c}/seq/depth/000000.png --camera {c}/seq/camera.yaml "
     "--detections {c}/roi.json --out {c}/out/roi",
     {kCamera, kDepth, kColor, kRoiDet, kOut}},
    {"detect_grape",
     "detect grape --color {c}/seq/color/000000.png --depth {c}/seq/depth/000000.png --camera {c}/seq/camera.yaml "
     "--detections {c}/roi.json --segmenter {c}/grape.json --threads 1 --out {c}/out/g",
     {kCamera, kDepth, kColor, kRoiDet, kGrapeModel, set("cut_point.min_points", "1"), kOut}},
    {"stereo_disparity",
     "stereo disparity --left {c}/sd/pair_000/left.png --right {c}/sd/pair_000/right.png --calib {c}/sd/rig.yaml "
     "--max-disp 64 --out {c}/out/d.png",
     {kLeft, kRig, kOut}},
    {"detect_seedling",
     "detect seedling --left {c}/sd/pair_000/left.png --right {c}/sd/pair_000/right.png --calib {c}/sd/rig.yaml "
     "--out {c}/out/s.json",
     {kLeft, kRig, kOut}},
    {"eval_seedling", "eval seedling --data {c}/sd --no-opencv --quiet", {kLeft, kRig, kSeedTruth}},
    {"detect_objects",
     "detect objects --model {c}/det.onnx --images {c}/images --out {c}/out/o",
     {kFolderImage, kOnnx, kOut}},
    {"export_detector", "export-detector --model {c}/det.pt --out {c}/out/d.onnx", {kPt, kOut}},
    {"calibrate_detector",
     "tune-mask-thresholds --model {c}/det.pt --coco {c}/coco.json --images {c}/images --classes bunch,peduncle "
     "--out {c}/out/c.pt",
     {kPt, kCocoGt, kImage, kOut}},
    {"eval_detector",
     "eval detector --coco {c}/coco.json --images {c}/images --model {c}/det.onnx",
     {kCocoGt, kImage, kOnnx}},
    {"train_detector",
     "train detector --coco {c}/coco.json --images {c}/images --out {c}/out/t.pt --epochs 1 --input-size 64x64",
     {kCocoGt, kImage, kOut}},
    {"eval_potato_detection",
     "eval potato-detection --images {c}/images --annotations {c}/voc --detections {c}/dets",
     {kVoc}},
#if CROPSIGHT_HAS_ROS
    {"export_bag", "export --data {c}/seq --out {c}/out/s.bag", {kCamera, kDepth, kColor, kOut}},
    {"import_bag", "import --data {c}/s.bag --out {c}/out/imp", {kBag, kOut}},
    {"detect_broccoli_bag",
     "detect broccoli --data {c}/s.bag --model {c}/broccoli.json --out {c}/out/d.jsonl --quiet",
     {kBag, kBroccoliModel, kOut}},
    {"harvest_potato_bag", "harvest potato --data {c}/s.bag --out {c}/out/h.jsonl", {kBag, kOut}},
#endif
  };
  return r;
}

class BadInputMatrix : public cropsight::testing::CliInputsSuite<Row> {
 protected:
  // A cell folder with an empty out/: the top-level entry holding `broken` is copied, every
  // other one linked.
  static void make_bad_input_cell(const fs::path& cell, const std::string& broken) {
    make_cell(cell, broken);
    fs::create_directories(cell / "out");
  }
};

// The good inputs must work (else every bad cell would "pass" for the wrong reason): the command
// succeeds on the unbroken cell. Slow commands (training) are checked elsewhere in tests/cli.
TEST_P(BadInputMatrix, Cells) {
  ASSERT_TRUE(ok()) << "fixture simulation failed";
  const Row& row = GetParam();
  {
    cropsight::testing::TempDir t;
    make_bad_input_cell(t / "cell", "");
    const CommandResult good = run_cli(replace_all(row.args, "{c}", (t / "cell").string()));
    ASSERT_EQ(good.exit_code, 0) << "the good inputs fail: " << good.err;
  }
  int cells = 0, failed = 0;
  std::string failures;
  for (const Input& in : row.inputs) {
    for (Bad b : classes_of(in.kind)) {
      if (std::find(in.na.begin(), in.na.end(), b) != in.na.end()) continue;
      cropsight::testing::TempDir t;
      const fs::path cell = t / "cell";
      make_bad_input_cell(cell, in.kind == Kind::Set ? "" : in.path);
      std::string args = replace_all(row.args, "{c}", cell.string());
      std::string names;  // what the line must name
      if (in.kind == Kind::Set) {
        args += " --set " + in.key + "=" + shell_quoted(b == Bad::UnknownKey ? "1" : raw_value(Kind::Set, b, in));
        if (b == Bad::UnknownKey) args = replace_all(args, "--set " + in.key + "=", "--set no_such_key_xyz=");
        names = b == Bad::UnknownKey ? "no_such_key_xyz" : in.key;
      } else if (in.kind == Kind::Output) {
        fs::remove_all(cell / "out");
        spit(cell / "out", "a file where the output folder belongs\n");
        names = (cell / "out").string();
      } else {
        make_bad(cell / in.path, in, b);
        names = fs::path(in.path).filename().string();
        // A missing frame (or a folder in its place) breaks the sequence's numbering: naming the
        // sequence folder is the right message then.
        if (in.path.rfind("seq/", 0) == 0 && in.kind == Kind::Png && (b == Bad::Missing || b == Bad::Directory))
          names = (cell / "seq").string();
      }
      const auto before = snapshot(cell);
      const CommandResult r = run_cli(args);
      const auto after = snapshot(cell);
      ++cells;
      std::string why;
      if (r.exit_code != 2) why += " exit " + std::to_string(r.exit_code) + ";";
      if (std::count(r.err.begin(), r.err.end(), '\n') != 1)
        why += " stderr has " + std::to_string(std::count(r.err.begin(), r.err.end(), '\n')) + " lines;";
      if (r.err.rfind("cropsight: ", 0) != 0) why += " no 'cropsight: ' prefix;";
      if (r.err.find(names) == std::string::npos) why += " does not name '" + names + "';";
      if (before != after) why += " the folder changed;";
      if (!why.empty()) {
        ++failed;
        std::string first = r.err.substr(0, r.err.find('\n'));
        failures += "  " + in.path + " / " + name_of(b) + ":" + why +
                    " stderr: " + replace_all(first.substr(0, 300), cell.string(), "CELL") + "\n";
      }
    }
  }
  // One summary line per command for docs/reliability.md (grep "matrix:").
  std::printf("matrix: %s %d cells, %d pass, %d fail\n", row.name.c_str(), cells, cells - failed, failed);
  EXPECT_EQ(failed, 0) << row.name << ":\n" << failures;
}

INSTANTIATE_TEST_SUITE_P(Commands, BadInputMatrix, ::testing::ValuesIn(rows()),
                         [](const ::testing::TestParamInfo<Row>& p) { return p.param.name; });

}  // namespace
