// Experiment: exports simulated broccoli sequences as a COCO set of depth-encoded
// images with one "head" class and polygon masks from the label images, so that
// `cropsight train detector --coco` can learn a depth segmenter of heads.
//
//   broccoli_depth_coco OUT_DIR STEP seq[,seq...]
//
// Encoding: cropsight/pipeline/broccoli/depth_encoding.hpp (what the detector feeds the CNN).
#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "coco_polygons.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/output.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/pipeline/broccoli/depth_encoding.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

int run(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: broccoli_depth_coco OUT_DIR STEP seq[,seq...]\n");
    return 2;
  }
  const int step = std::max(1, std::atoi(argv[2]));
  std::vector<fs::path> seqs;
  {
    std::stringstream list(argv[3]);
    for (std::string dir; std::getline(list, dir, ',');) seqs.emplace_back(dir);
  }
  // A new folder (or an earlier export, with --force semantics off): never a user's folder.
  cropsight::io::OutputFolder folder(argv[1], {"broccoli_depth_coco", false, seqs});
  const fs::path& out = folder.path();
  json images = json::array(), annotations = json::array();
  int image_id = 0, ann_id = 0;
  std::stringstream ss(argv[3]);
  for (std::string dir; std::getline(ss, dir, ',');) {
    const cropsight::io::SequenceReader seq(dir);
    for (int i = 0; i < seq.size(); i += step) {
      const cropsight::RgbdFrame f = seq.read(i);
      const std::string name = fs::path(dir).filename().string() + "-" + std::to_string(i) + ".png";
      cropsight::io::write_color(out / name,
                                 cropsight::pipeline::broccoli::encode_depth_for_cnn(f.depth, f.camera.depth_scale));
      ++image_id;
      images.push_back({{"id", image_id}, {"file_name", name}, {"width", f.depth.width}, {"height", f.depth.height}});
      std::map<int, cv::Mat> masks;
      for (int v = 0; v < f.depth.height; ++v)
        for (int u = 0; u < f.depth.width; ++u) {
          const std::size_t k = std::size_t(v) * f.depth.width + u;
          const int id = f.labels.data[k];
          if (!id || !f.depth.data[k]) continue;
          auto [it, fresh] = masks.try_emplace(id);
          if (fresh) it->second = cv::Mat::zeros(f.depth.height, f.depth.width, CV_8U);
          it->second.at<std::uint8_t>(v, u) = 255;
        }
      for (const auto& [id, m] : masks) {
        if (cv::countNonZero(m) < 30) continue;
        const cv::Rect b = cv::boundingRect(m);
        json poly = cropsight::tools::coco_polygons(m);
        if (poly.empty()) continue;
        annotations.push_back({{"id", ++ann_id},
                               {"image_id", image_id},
                               {"category_id", 1},
                               {"bbox", {b.x, b.y, b.width, b.height}},
                               {"area", cv::countNonZero(m)},
                               {"iscrowd", 0},
                               {"segmentation", poly}});
      }
    }
    std::fprintf(stderr, "%s: %d images, %d heads so far\n", dir.c_str(), image_id, ann_id);
  }
  json coco = {
      {"images", images}, {"annotations", annotations}, {"categories", json::array({{{"id", 1}, {"name", "head"}}})}};
  // The folder appears whole: an interrupted export leaves nothing at OUT_DIR.
  cropsight::io::write_file_atomic(out / "annotations.json", coco.dump());
  folder.commit("COCO export");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {  // cropsight::Error names the file; one line, exit 2
    std::fprintf(stderr, "broccoli_depth_coco: %s\n", e.what());
    return 2;
  }
}
