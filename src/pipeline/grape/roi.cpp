#include "cropsight/pipeline/grape/roi.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <tuple>

#include "cropsight/core/error.hpp"
#include "cropsight/geometry/knn_normals.hpp"

namespace cropsight::pipeline::grape {

void RoiConfig::validate(const std::string& where) const {
  check_config(*this, where);
  // One id for both kinds would pair every box with itself.
  if (peduncle_category == bunch_category)
    throw Error(where, "'peduncle_category' must differ from bunch_category, got " + std::to_string(peduncle_category));
  cropsight::detail::check_range(where, "z_max", z_max, Range::above(z_min, "z_min"));
}

Box2D roi_from_boxes(const Box2D& g, const Box2D& p) {
  Box2D r;
  r.x = g.x;
  r.y = p.y;
  r.width = g.width;
  r.height = g.y + g.height - p.y;
  return r;
}

namespace {
Box2D unite(const Box2D& a, const Box2D& b) {
  const int x0 = std::min(a.x, b.x), y0 = std::min(a.y, b.y);
  const int x1 = std::max(a.x + a.width, b.x + b.width), y1 = std::max(a.y + a.height, b.y + b.height);
  return {x0, y0, x1 - x0, y1 - y0};
}
bool overlap(const Box2D& a, const Box2D& b) {
  return std::min(a.x + a.width, b.x + b.width) > std::max(a.x, b.x) &&
         std::min(a.y + a.height, b.y + b.height) > std::max(a.y, b.y);
}
Box2D clip(const Box2D& b, int w, int h) {
  const int x0 = std::clamp(b.x, 0, w), y0 = std::clamp(b.y, 0, h);
  const int x1 = std::clamp(b.x + b.width, 0, w), y1 = std::clamp(b.y + b.height, 0, h);
  return {x0, y0, x1 - x0, y1 - y0};
}
}  // namespace

std::vector<Box2D> merge_overlapping(std::vector<Box2D> boxes) {
  bool merged = true;
  while (merged) {
    merged = false;
    for (std::size_t i = 0; i < boxes.size() && !merged; ++i)
      for (std::size_t j = i + 1; j < boxes.size(); ++j)
        if (overlap(boxes[i], boxes[j])) {
          boxes[i] = unite(boxes[i], boxes[j]);
          boxes.erase(boxes.begin() + long(j));
          merged = true;
          break;
        }
  }
  return boxes;
}

std::vector<Box2D> grape_rois(const std::vector<Detection>& dets, int width, int height, const RoiConfig& cfg) {
  cfg.validate("grape roi config");
  std::vector<Box2D> rois;
  for (const auto& g : dets) {
    if (g.category != cfg.bunch_category || g.score < cfg.min_score || g.box.empty()) continue;
    const Detection* best = nullptr;
    int best_gap = std::numeric_limits<int>::max();
    for (const auto& p : dets) {
      if (p.category != cfg.peduncle_category || p.score < cfg.min_score || p.box.empty()) continue;
      const int cx = p.box.x + p.box.width / 2;
      if (cx < g.box.x || cx > g.box.x + g.box.width || p.box.y >= g.box.y) continue;
      const int gap = g.box.y - (p.box.y + p.box.height);  // how far above the bunch it ends
      if (std::abs(gap) < best_gap) best_gap = std::abs(gap), best = &p;
    }
    rois.push_back(best ? roi_from_boxes(g.box, best->box) : g.box);
  }
  std::vector<Box2D> out;
  for (const auto& r : merge_overlapping(rois)) {
    const Box2D c = clip(r, width, height);
    if (!c.empty()) out.push_back(c);
  }
  return out;
}

Cloud roi_cloud(const DepthImage& depth, const ColorImage& color, const CameraIntrinsics& cam, const Box2D& roi,
                const RoiConfig& cfg) {
  if (!color.empty() && (color.width != depth.width || color.height != depth.height))
    throw Error("roi cloud", "colour and depth images differ in size");
  if (cam.width != depth.width || cam.height != depth.height)
    throw Error("roi cloud", "camera size " + std::to_string(cam.width) + "x" + std::to_string(cam.height) +
                                 " differs from depth image " + std::to_string(depth.width) + "x" +
                                 std::to_string(depth.height));
  const Box2D r = clip(roi, depth.width, depth.height);
  Cloud c;
  for (int v = r.y; v < r.y + r.height; ++v)
    for (int u = r.x; u < r.x + r.width; ++u) {
      const double z = double(depth.at(u, v)) * cam.depth_scale;
      if (!(z > cfg.z_min && z < cfg.z_max)) continue;
      c.points.push_back(cam.deproject(float(u), float(v), float(z)));
      if (!color.empty()) {
        const Rgb8 px = color.at(u, v);
        c.colors.emplace_back(px.r / 255.f, px.g / 255.f, px.b / 255.f);
      }
    }
  return c;
}

RoiCloud segmenter_input(Cloud cloud, const RoiConfig& cfg) {
  RoiCloud r;
  r.cloud = std::move(cloud);
  if (!r.cloud.has_normals()) {
    geometry::KnnNormalsConfig ncfg;
    ncfg.k = std::min(cfg.normal_k, int(r.cloud.size()));  // no more neighbours than points
    ncfg.viewpoint = Eigen::Vector3f::Zero();              // the camera centre, in the camera frame
    r.cloud.normals = geometry::knn_normals(r.cloud.points, ncfg);
  }
  std::tie(r.centroid, r.scale) = geometry::normalize_unit_sphere(r.cloud.points);
  r.cloud.labels.assign(r.cloud.size(), 0);
  return r;
}

RoiFrame grape_roi_clouds(const DepthImage& depth, const ColorImage& color, const CameraIntrinsics& cam,
                          const std::vector<Detection>& detections, const RoiConfig& cfg) {
  cfg.validate("grape roi config");
  if (cam.width != depth.width || cam.height != depth.height)
    throw Error("roi cloud", "camera size differs from the depth image");
  RoiFrame frame;
  for (const auto& d : detections) {
    if (d.category != cfg.bunch_category && d.category != cfg.peduncle_category) continue;
    const Box2D& b = d.box;
    if (b.x >= depth.width || b.y >= depth.height || b.x + b.width <= 0 || b.y + b.height <= 0)
      frame.outside.push_back(d);
  }
  for (const auto& box : grape_rois(detections, depth.width, depth.height, cfg)) {
    Cloud cloud = roi_cloud(depth, color, cam, box, cfg);
    if (cloud.size() < 3) continue;  // nothing measurable in this ROI
    RoiCloud r = segmenter_input(std::move(cloud), cfg);
    r.box = box;
    frame.rois.push_back(std::move(r));
  }
  return frame;
}

namespace {

// The file's entries in file order with their image_id (-1 when they have none): every entry, or
// with `only` >= 0 that image's (the others are skipped unchecked).
std::vector<std::pair<long, Detection>> read_coco_entries(const std::filesystem::path& path, long only) {
  const std::string where = path.string();
  std::ifstream in(path);
  if (!in) throw Error(where, "cannot open file");
  nlohmann::json j;
  try {
    in >> j;
  } catch (const std::exception& e) {
    throw Error(where, std::string("not valid JSON: ") + e.what());
  }
  const nlohmann::json* arr = &j;
  if (j.is_object()) {
    if (!j.contains("annotations") || !j["annotations"].is_array())
      throw Error(where, "expected a COCO file with an \"annotations\" array or a results array");
    arr = &j["annotations"];
  }
  if (!arr->is_array()) throw Error(where, "expected a JSON array of detections");
  std::vector<std::pair<long, Detection>> out;
  std::size_t k = 0;
  for (const auto& a : *arr) {
    const std::string item = "annotation " + std::to_string(k++);
    if (!a.is_object() || !a.contains("bbox") || !a["bbox"].is_array() || a["bbox"].size() != 4 ||
        !a.contains("category_id") || !a["category_id"].is_number_integer())
      throw Error(where, item + ": needs \"bbox\" [x, y, w, h] and an integer \"category_id\"");
    // Integers and bounded coordinates only: nlohmann's get<long>() of 2e119, or int(floor(1e300)),
    // is undefined behaviour (as fuzzing finding 24).
    if (a.contains("image_id") && !a["image_id"].is_number_integer())
      throw Error(where, item + ": \"image_id\" must be an integer");
    if (only >= 0 && a.value("image_id", -1L) != only) continue;
    double b[4];
    for (int i = 0; i < 4; ++i) {
      if (!a["bbox"][std::size_t(i)].is_number()) throw Error(where, item + ": bbox values must be numbers");
      b[i] = a["bbox"][std::size_t(i)].get<double>();
      if (std::abs(b[i]) > 1e6) throw Error(where, item + ": bbox values must lie within a million pixels");
    }
    if (b[2] < 0 || b[3] < 0) throw Error(where, item + ": negative bbox size");
    Detection d;
    d.annotation = long(k - 1);
    d.box = {int(std::floor(b[0])), int(std::floor(b[1])), int(std::ceil(b[2])), int(std::ceil(b[3]))};
    d.category = int(std::clamp<std::int64_t>(a["category_id"].get<std::int64_t>(), -1, 1 << 20));
    d.score = a.contains("score") && a["score"].is_number() ? a["score"].get<float>() : 1.f;
    out.emplace_back(a.value("image_id", -1L), d);
  }
  return out;
}

}  // namespace

std::vector<Detection> read_coco_detections(const std::filesystem::path& path, long image_id) {
  std::vector<Detection> out;
  for (auto& [id, d] : read_coco_entries(path, image_id)) out.push_back(d);
  return out;
}

std::map<long, std::vector<Detection>> read_coco_detections_by_image(const std::filesystem::path& path) {
  std::map<long, std::vector<Detection>> out;
  for (auto& [id, d] : read_coco_entries(path, -1)) out[id].push_back(d);
  return out;
}

}  // namespace cropsight::pipeline::grape
