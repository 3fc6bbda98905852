#include "cropsight/pipeline/seedling/truth.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "cropsight/core/config.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/stereo/calibration.hpp"
#include "cropsight/stereo/stereo_io.hpp"
#include "io/json_file.hpp"

namespace cropsight::pipeline::seedling {

namespace fs = std::filesystem;

namespace {

// A zero or non-finite box or plane would make the volume ratio and the top-view IoU meaningless.
void check_truth(const Truth& t, const fs::path& path) {
  for (const auto& [key, v] :
       {std::pair{"envelope.length_m", t.envelope.length}, std::pair{"envelope.width_m", t.envelope.width},
        std::pair{"envelope.height_m", t.envelope.height}})
    if (!(std::isfinite(v) && v > 0))
      throw Error(path.string(),
                  std::string("'") + key + "' must be a finite number > 0, got " + cropsight::detail::format_value(v));
  const Eigen::Vector3d& n = t.plane_normal;
  if (!(n.allFinite() && std::fabs(n.norm() - 1) < 1e-3 && std::isfinite(t.plane_d)))
    throw Error(path.string(), "'plane' needs a unit normal and a finite d");
}

}  // namespace

Truth read_truth(const fs::path& p) {
  Truth t;
  // The simulator writes 16-bit disparity x 256 and an 8-bit mask; read_gray rejects a 16-bit mask.
  t.disparity = stereo::read_disparity(p / "disparity.png", 256.0, 16);
  t.mask = stereo::read_gray(p / "mask.png");
  const fs::path path = p / "truth.json";
  const nlohmann::json j = io::detail::read_json_file(path);
  try {
    t.envelope.length = j.at("envelope").at("length_m").get<double>();
    t.envelope.width = j.at("envelope").at("width_m").get<double>();
    t.envelope.height = j.at("envelope").at("height_m").get<double>();
    const auto nn = j.at("plane").at("normal");
    t.plane_normal = Eigen::Vector3d(nn.at(0).get<double>(), nn.at(1).get<double>(), nn.at(2).get<double>());
    t.plane_d = j.at("plane").at("d").get<double>();
  } catch (const nlohmann::json::exception& e) {
    throw Error(path.string(), std::string("missing or malformed key: ") + e.what());
  }
  check_truth(t, path);
  return t;
}

Dataset open_dataset(const fs::path& dir, const fs::path& calib_path) {
  if (!fs::is_directory(dir)) throw Error(dir.string(), "data folder not found");
  const auto calib = stereo::load_calibration(calib_path.empty() ? dir / "rig.yaml" : calib_path);
  if (!stereo::is_rectified(calib))
    throw Error(dir.string(), "evaluation expects the simulator's rectified pairs (rig.yaml of an ideal rig)");
  Dataset ds{dir, stereo::rectified_geometry(calib), {}};
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_directory() && e.path().filename().string().rfind("pair_", 0) == 0) ds.pairs.push_back(e.path());
  std::sort(ds.pairs.begin(), ds.pairs.end());
  if (ds.pairs.empty()) throw Error(dir.string(), "no pair_* folders (make them with cropsight simulate seedling)");
  return ds;
}

std::pair<ColorImage, ColorImage> read_pair(const fs::path& p) {
  return stereo::read_color_pair(p / "left.png", p / "right.png");
}

}  // namespace cropsight::pipeline::seedling
