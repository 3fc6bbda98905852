// pipeline/potato: listing the paper's orientation folders and evaluating a configuration on them.
#include "cropsight/pipeline/potato/orientation_dataset.hpp"

#include <algorithm>
#include <map>
#include <numbers>
#include <regex>
#include <tuple>

#include "cropsight/core/error.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/io/image_io.hpp"

namespace cropsight::pipeline::potato {

namespace fs = std::filesystem;

namespace {

struct Folder {
  double angle = 0;
  std::string light;
  fs::path path;
};

// `<angle>_<light>_<kind>` sub-folders of `dir`, keyed by "<angle>_<light>".
std::map<std::string, Folder> folders(const fs::path& dir, const std::string& kind) {
  if (!fs::is_directory(dir)) throw Error(dir.string(), "not a folder");
  const std::regex re("([0-9]+(?:\\.[0-9]+)?)_([A-Za-z]+)_" + kind);
  std::map<std::string, Folder> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    std::smatch m;
    const std::string name = e.path().filename().string();
    if (e.is_directory() && std::regex_match(name, m, re))
      out[m[1].str() + "_" + m[2].str()] = {std::stod(m[1].str()), m[2].str(), e.path()};
  }
  return out;
}

// imageN.png files of a folder, keyed by N.
std::map<int, fs::path> numbered_images(const fs::path& dir) {
  static const std::regex re("image([0-9]+)\\.png");
  std::map<int, fs::path> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    std::smatch m;
    const std::string name = e.path().filename().string();
    if (e.is_regular_file() && std::regex_match(name, m, re)) out[std::stoi(m[1].str())] = e.path();
  }
  return out;
}

}  // namespace

std::vector<OrientationShot> list_orientation_shots(const fs::path& rgb_dir, const fs::path& depth_dir) {
  const auto rgb = folders(rgb_dir, "rgb");
  const auto depth = folders(depth_dir, "depth");
  std::vector<OrientationShot> shots;
  for (const auto& [key, f] : rgb) {
    const auto d = depth.find(key);
    if (d == depth.end()) throw Error(f.path.string(), "no matching " + key + "_depth folder in " + depth_dir.string());
    const auto depth_images = numbered_images(d->second.path);
    for (const auto& [n, path] : numbered_images(f.path)) {
      // The partner: same number, else the next, else the previous.
      fs::path partner;
      for (int k : {n, n + 1, n - 1})
        if (const auto it = depth_images.find(k); it != depth_images.end()) {
          partner = it->second;
          break;
        }
      if (partner.empty()) throw Error(path.string(), "no depth image numbered " + std::to_string(n) + " or ±1");
      shots.push_back({path, partner, f.angle, f.light, n, n <= 13 ? 1 : 2});
    }
  }
  if (shots.empty()) throw Error(rgb_dir.string(), "no <angle>_<light>_rgb/imageN.png shots");
  std::sort(shots.begin(), shots.end(), [](const OrientationShot& a, const OrientationShot& b) {
    return std::tie(a.angle_deg, a.light, a.number) < std::tie(b.angle_deg, b.light, b.number);
  });
  return shots;
}

eval::OrientationEvaluation evaluate_orientation(const std::vector<OrientationShot>& shots, Detector2D& detector,
                                                 const measure::OrientationConfig& cfg) {
  measure::validate(cfg);
  std::vector<eval::OrientationSample> samples;
  for (const auto& s : shots) {
    const ColorImage rgb = io::read_color(s.rgb);
    const fs::path& used = cfg.input == measure::OrientationInput::depth ? s.depth : s.rgb;
    eval::OrientationSample out{used.string(), s.potato, s.light, s.angle_deg, false, 0, 0};
    const auto boxes = detector.detect(DetectorInput{&rgb, nullptr});
    if (!boxes.empty()) {
      ColorImage depth;
      if (cfg.input == measure::OrientationInput::depth) {
        depth = io::read_color(s.depth);
        if (depth.width != rgb.width || depth.height != rgb.height)
          throw Error(s.depth.string(), "size differs from its RGB image " + s.rgb.string());
      }
      const ColorImage& image = cfg.input == measure::OrientationInput::depth ? depth : rgb;
      Stopwatch watch;
      const auto r = measure::estimate_orientation(image, boxes.front(), cfg, out.file);
      out.ms = watch.ms();
      out.ok = r.ok;
      out.estimate_deg = r.angle_rad * 180.0 / std::numbers::pi;
    }
    samples.push_back(out);
  }
  return eval::summarise_orientation(std::move(samples));
}

}  // namespace cropsight::pipeline::potato
