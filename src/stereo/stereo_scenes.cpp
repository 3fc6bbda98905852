#include "cropsight/stereo/stereo_scenes.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>
#include <string>
#include <tuple>

#include "cropsight/core/error.hpp"
#include "cropsight/stereo/stereo_io.hpp"

namespace cropsight::stereo {

namespace fs = std::filesystem;

namespace {

// The first of `names` that exists in `dir`.
std::optional<fs::path> first_existing(const fs::path& dir, std::initializer_list<const char*> names) {
  for (const char* n : names)
    if (fs::is_regular_file(dir / n)) return dir / n;
  return std::nullopt;
}

bool is_scene_layout(const fs::path& d) {
  return fs::is_regular_file(d / "left.png") && fs::is_regular_file(d / "right.png") &&
         fs::is_regular_file(d / "scene.yaml") && first_existing(d, {"gt.pfm", "gt.png", "gt.pgm"});
}

bool is_middlebury2014_layout(const fs::path& d) {
  return fs::is_regular_file(d / "im0.png") && fs::is_regular_file(d / "im1.png") &&
         fs::is_regular_file(d / "calib.txt") && first_existing(d, {"disp0GT.pfm", "disp0.pfm"});
}

// scene.yaml: gt_scale (> 0) and max_disparity (1..kMaxDisparities).
std::pair<double, int> read_scene_yaml(const fs::path& file) {
  YAML::Node n;
  try {
    n = YAML::LoadFile(file.string());
  } catch (const YAML::Exception& e) {
    throw Error(file.string(), std::string("cannot parse: ") + e.what());
  }
  auto get = [&](const char* key, auto value) {
    if (!n.IsMap() || !n[key]) throw Error(file.string(), std::string("missing '") + key + "'");
    try {
      return n[key].as<decltype(value)>();
    } catch (const YAML::Exception&) {
      throw Error(file.string(), std::string("'") + key + "' is not a number");
    }
  };
  const double scale = get("gt_scale", 0.0);
  const int maxd = get("max_disparity", 0);
  if (!(scale > 0) || !std::isfinite(scale)) throw Error(file.string(), "'gt_scale' must be > 0");
  if (maxd < 1 || maxd > kMaxDisparities)
    throw Error(file.string(), "'max_disparity' must lie in 1.." + std::to_string(kMaxDisparities));
  return {scale, maxd};
}

// calib.txt of Middlebury 2014: "key=value" lines; ndisp is the search range.
int read_ndisp(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw Error(file.string(), "cannot open");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("ndisp=", 0) != 0) continue;
    try {
      const int v = std::stoi(line.substr(6));
      if (v < 1 || v > kMaxDisparities)
        throw Error(file.string(), "'ndisp' must lie in 1.." + std::to_string(kMaxDisparities));
      return v;
    } catch (const std::logic_error&) {
      throw Error(file.string(), "'ndisp' is not a number");
    }
  }
  throw Error(file.string(), "missing 'ndisp='");
}

void check_truth(const DisparityImage& t, const MiddleburyPair& p, const fs::path& file) {
  if (t.width != p.left.width || t.height != p.left.height)
    throw Error(file.string(), "ground truth size " + std::to_string(t.width) + "x" + std::to_string(t.height) +
                                   " differs from the images (" + std::to_string(p.left.width) + "x" +
                                   std::to_string(p.left.height) + ")");
}

int largest_disparity(const DisparityImage& t) {
  float m = 0;
  for (float v : t.data)
    if (std::isfinite(v)) m = std::max(m, v);
  return int(std::ceil(m));
}

}  // namespace

bool is_stereo_scene(const fs::path& dir) { return is_scene_layout(dir) || is_middlebury2014_layout(dir); }

MiddleburyPair load_stereo_scene(const fs::path& dir) {
  if (!fs::is_directory(dir)) throw Error(dir.string(), "scene folder not found");
  MiddleburyPair p;
  p.name = dir.filename().string();
  if (p.name.empty()) p.name = dir.parent_path().filename().string();
  fs::path gt;
  std::optional<fs::path> gt_right;
  int range = 0;
  double scale = 1;
  if (is_scene_layout(dir)) {
    std::tie(p.left, p.right) = read_color_pair(dir / "left.png", dir / "right.png");
    std::tie(scale, range) = read_scene_yaml(dir / "scene.yaml");
    gt = *first_existing(dir, {"gt.pfm", "gt.png", "gt.pgm"});
    gt_right = first_existing(dir, {"gt_right.pfm", "gt_right.png", "gt_right.pgm"});
  } else if (is_middlebury2014_layout(dir)) {
    std::tie(p.left, p.right) = read_color_pair(dir / "im0.png", dir / "im1.png");
    range = read_ndisp(dir / "calib.txt");
    gt = *first_existing(dir, {"disp0GT.pfm", "disp0.pfm"});
    gt_right = first_existing(dir, {"disp1GT.pfm", "disp1.pfm"});
  } else {
    throw Error(dir.string(),
                "not a stereo scene: expected left.png, right.png, gt.{png,pgm,pfm}, scene.yaml or im0.png, "
                "im1.png, disp0GT.pfm, calib.txt");
  }
  p.truth = read_ground_truth(gt, scale);
  check_truth(p.truth, p, gt);
  if (std::none_of(p.truth.data.begin(), p.truth.data.end(), [](float v) { return std::isfinite(v); }))
    throw Error(gt.string(), "ground truth has no valid pixel; nothing to score");
  p.max_disparity = largest_disparity(p.truth);
  // The matchers need 16 | range <= image width.
  const int cap = std::min(kMaxDisparities, (p.left.width / 16) * 16);
  p.num_disparities = std::clamp(((range + 15) / 16) * 16, 16, std::max(16, cap));
  if (gt_right) {
    const DisparityImage rt = read_ground_truth(*gt_right, scale);
    check_truth(rt, p, *gt_right);
    p.nonoccluded = nonoccluded_mask(p.truth, rt, 1.0, gt_right->string());
  } else if (const auto mask = first_existing(dir, {"mask0nocc.png"})) {
    const GrayImage m = read_gray(*mask);
    if (m.width != p.left.width || m.height != p.left.height)
      throw Error(mask->string(), "mask size differs from the images");
    p.nonoccluded = GrayImage(m.width, m.height, 0);
    for (std::size_t i = 0; i < m.size(); ++i) p.nonoccluded.data[i] = m.data[i] == 255 ? 255 : 0;
  }
  return p;
}

std::vector<MiddleburyPair> load_stereo_scenes(const fs::path& dir) {
  if (!fs::is_directory(dir)) throw Error(dir.string(), "scene folder not found");
  if (is_stereo_scene(dir)) return {load_stereo_scene(dir)};
  std::vector<fs::path> subs;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_directory() && is_stereo_scene(e.path())) subs.push_back(e.path());
  std::sort(subs.begin(), subs.end());
  if (subs.empty())
    throw Error(dir.string(),
                "holds no stereo scene (subfolders with left.png, right.png, gt.*, scene.yaml or Middlebury 2014 "
                "im0.png, im1.png, disp0GT.pfm, calib.txt)");
  std::vector<MiddleburyPair> out;
  for (const auto& s : subs) out.push_back(load_stereo_scene(s));
  return out;
}

}  // namespace cropsight::stereo
