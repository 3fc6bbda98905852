#pragma once
// The good inputs the CLI matrices run the commands on, made once per suite under `b`: a 2-frame
// simulated broccoli sequence (seq/), one seedling pair with its rig (sd/), three grape clouds
// (clouds/points/), two small images with COCO and VOC truth (images/, coco.json, voc/, dets/),
// grape ROI boxes (roi.json), the shipped models (broccoli.json, preset.yaml, grape.json,
// det.onnx, det.pt) and, in builds with ROS, the sequence as a bag (s.bag). Returns false when a
// simulation failed.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>

#include "cli/recorder_layouts.hpp"
#include "cropsight/io/grape_text.hpp"
#include "pipeline/grape/grape_test_clouds.hpp"
#include "testing/testing.hpp"

namespace cropsight::testing {

inline bool make_cli_inputs(const std::filesystem::path& b) {
  namespace fs = std::filesystem;
  const fs::path src = source_dir();
  const auto spit = [](const fs::path& p, const std::string& text) { write_text(p, text); };

  bool ok =
      run_cli("simulate broccoli --frames 2 --seed 3 --out " + shell_quoted(b / "seq")).exit_code == 0 &&
      run_cli("simulate seedling --pairs 1 --calib-pairs 0 --quiet --out " + shell_quoted(b / "sd")).exit_code == 0;
  fs::copy_file(src / "models/broccoli-oes-uk.json", b / "broccoli.json");
  fs::copy_file(src / "configs/broccoli-oes-uk.yaml", b / "preset.yaml");
  fs::copy_file(src / "models/grape-gbdt-fast.json", b / "grape.json");
  fs::copy_file(src / "models/detector-grape.onnx", b / "det.onnx");
  fs::copy_file(src / "models/detector-grape.pt", b / "det.pt");
  // The pass as a RealSense recorder writes it: import's camera_info, extrinsics and poses inputs.
  if (ok) write_recorder_layout(io::SequenceReader(b / "seq"), b / "rec", Recorder::RealSense);
#if CROPSIGHT_HAS_ROS
  ok = ok && run_cli("export --data " + shell_quoted(b / "seq") + " --out " + shell_quoted(b / "s.bag")).exit_code == 0;
#endif
  fs::create_directories(b / "clouds/points");
  for (int i = 0; i < 3; ++i)
    cropsight::io::write_grape_text(b / "clouds/points" / ("c" + std::to_string(i) + ".txt"),
                                    two_blobs(std::uint32_t(i), 200));
  fs::create_directories(b / "images");
  fs::create_directories(b / "voc");
  fs::create_directories(b / "dets");
  for (const char* stem : {"a", "b"}) {
    cv::Mat img(64, 64, CV_8UC3);
    cv::randu(img, 0, 255);
    cv::imwrite((b / "images" / (std::string(stem) + ".png")).string(), img);
    spit(b / "voc" / (std::string(stem) + ".xml"),
         "<annotation><filename>" + std::string(stem) +
             ".png</filename><size><width>64</width><height>64</height><depth>3</depth></size><object>"
             "<name>potato</name><bndbox><xmin>10</xmin><ymin>10</ymin><xmax>30</xmax><ymax>30</ymax></bndbox>"
             "</object></annotation>\n");
    spit(b / "dets" / (std::string(stem) + ".txt"), "potato 0.9 10 10 30 30\n");
  }
  spit(
      b / "coco.json",
      R"({"images":[{"id":1,"file_name":"a.png","width":64,"height":64},{"id":2,"file_name":"b.png","width":64,"height":64}],)"
      R"("annotations":[{"id":1,"image_id":1,"category_id":1,"bbox":[10,10,20,20],"area":400,"iscrowd":0,)"
      R"("segmentation":[[10,10,30,10,30,30,10,30]]}],)"
      R"("categories":[{"id":1,"name":"bunch"},{"id":2,"name":"peduncle"}]})");
  spit(b / "roi.json", R"([{"image_id":0,"category_id":1,"bbox":[200,150,60,60],"score":0.9}])");
  return ok;
}

/// Every entry under `dir` (not through links) with a hash of its contents ("dir" for a folder,
/// "link" for a link): what "no file created, removed or changed" compares.
inline std::map<std::string, std::string> snapshot(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::map<std::string, std::string> s;
  for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator(); ++it) {
    const auto rel = fs::relative(it->path(), dir).string();
    if (it->is_symlink()) {
      s[rel] = "link";
    } else if (it->is_directory()) {
      s[rel] = "dir";
    } else {
      std::ifstream in(it->path(), std::ios::binary);
      std::stringstream text;
      text << in.rdbuf();
      s[rel] = std::to_string(std::hash<std::string>{}(text.str()));
    }
  }
  return s;
}

/// A parameterised suite over the CLI inputs: make_cli_inputs once per suite (ok() says whether it
/// worked), and cells, folders where one input is copied (a command may break or aim at it) and
/// every other one is a link to the suite's.
template <class Param>
class CliInputsSuite : public ::testing::TestWithParam<Param> {
 public:
  static void SetUpTestSuite() {
    base_ = new TempDir;
    ok_ = make_cli_inputs(base_->path());
  }
  static void TearDownTestSuite() {
    delete base_;
    base_ = nullptr;
  }

 protected:
  static const std::filesystem::path& inputs() { return base_->path(); }
  static bool ok() { return ok_; }
  /// Fills `cell` (created): the top-level input entry holding `copied` ("seq/depth/000000.png":
  /// seq) is copied, every other one linked.
  static void make_cell(const std::filesystem::path& cell, const std::string& copied) {
    namespace fs = std::filesystem;
    fs::create_directories(cell);
    const std::string top = copied.substr(0, copied.find('/'));
    for (const auto& e : fs::directory_iterator(base_->path())) {
      const auto name = e.path().filename().string();
      if (name == top)
        fs::copy(e.path(), cell / name, fs::copy_options::recursive);
      else
        fs::create_directory_symlink(e.path(), cell / name);  // works for files too on Linux
    }
  }

 private:
  static inline TempDir* base_ = nullptr;
  static inline bool ok_ = false;
};

}  // namespace cropsight::testing
