// COCO and VOC detection sets (include/cropsight/nn/detection_dataset.hpp).
#include "cropsight/nn/detection_dataset.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <random>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/voc.hpp"
#include "io/json_file.hpp"

namespace cropsight::nn {

namespace {

using nlohmann::json;

// A regular file at `p`; false, not a std::filesystem_error, for a name the system refuses (too
// long, a loop): the annotation's file name is data (fuzzing finding 21).
bool is_file(const std::filesystem::path& p) {
  std::error_code ec;
  return std::filesystem::is_regular_file(p, ec);
}

std::filesystem::path find_image(const std::filesystem::path& dir, const std::string& name) {
  for (const auto& p : {dir / name, dir / std::filesystem::path(name).filename()})
    if (is_file(p)) return p;
  return dir / name;
}

// The member `key` of `j`, which `where` names in messages; Error when absent or not `type`.
const json& member(const json& j, const char* key, json::value_t type, const std::string& file,
                   const std::string& where) {
  if (!j.is_object() || !j.contains(key)) throw Error(file, where + ": no '" + key + "'");
  const json& v = j.at(key);
  const bool ok = type == json::value_t::number_integer ? v.is_number_integer()
                  : type == json::value_t::number_float ? v.is_number()
                                                        : v.type() == type;
  if (!ok) throw Error(file, where + ": '" + key + "' has the wrong type");
  return v;
}

int class_of(const std::vector<std::string>& classes, const std::string& name) {
  const auto it = std::find(classes.begin(), classes.end(), name);
  return it == classes.end() ? -1 : int(it - classes.begin());
}

}  // namespace

std::map<std::string, long> coco_image_ids(const std::filesystem::path& annotations) {
  const std::string file = annotations.string();
  const json root = io::detail::read_json_file(annotations);
  const json& images = member(root, "images", json::value_t::array, file, "root");
  std::map<std::string, long> ids;
  for (std::size_t i = 0; i < images.size(); ++i) {
    const std::string where = "images[" + std::to_string(i) + "]";
    const long id = member(images[i], "id", json::value_t::number_integer, file, where).get<long>();
    const std::string name = member(images[i], "file_name", json::value_t::string, file, where).get<std::string>();
    if (!ids.emplace(std::filesystem::path(name).filename().string(), id).second)
      throw Error(file, where + ": a second image named '" + std::filesystem::path(name).filename().string() + "'");
  }
  return ids;
}

// Long on purpose: COCO images, categories and annotations read and checked in one pass over the file.
DetectionDataset read_coco_detection(const std::filesystem::path& annotations, const std::filesystem::path& images_dir,
                                     const std::vector<std::string>& classes) {
  const std::string file = annotations.string();
  const json root = io::detail::read_json_file(annotations);
  DetectionDataset out;
  out.classes = classes;
  // Categories: id → class index.
  std::map<long, int> category_class;
  const json& cats = member(root, "categories", json::value_t::array, file, "root");
  std::vector<std::pair<long, std::string>> by_id;
  for (std::size_t i = 0; i < cats.size(); ++i) {
    const std::string where = "categories[" + std::to_string(i) + "]";
    by_id.emplace_back(member(cats[i], "id", json::value_t::number_integer, file, where).get<long>(),
                       member(cats[i], "name", json::value_t::string, file, where).get<std::string>());
  }
  std::sort(by_id.begin(), by_id.end());
  if (out.classes.empty())
    for (const auto& [id, name] : by_id)
      if (name != "_background_") out.classes.push_back(name);
  if (out.classes.empty()) throw Error(file, "categories: no class to detect");
  for (const auto& [id, name] : by_id)
    if (const int c = class_of(out.classes, name); c >= 0) category_class[id] = c;
  // Images.
  std::map<long, std::size_t> image_index;
  const json& images = member(root, "images", json::value_t::array, file, "root");
  for (std::size_t i = 0; i < images.size(); ++i) {
    const std::string where = "images[" + std::to_string(i) + "]";
    const long id = member(images[i], "id", json::value_t::number_integer, file, where).get<long>();
    const std::string name = member(images[i], "file_name", json::value_t::string, file, where).get<std::string>();
    DetectionSample s;
    s.name = name;
    s.image = io::read_color(find_image(images_dir, name));
    image_index[id] = out.samples.size();
    out.samples.push_back(std::move(s));
  }
  // Annotations.
  const json& anns = member(root, "annotations", json::value_t::array, file, "root");
  for (std::size_t i = 0; i < anns.size(); ++i) {
    const std::string where = "annotations[" + std::to_string(i) + "]";
    const json& a = anns[i];
    const long image_id = member(a, "image_id", json::value_t::number_integer, file, where).get<long>();
    const long cat = member(a, "category_id", json::value_t::number_integer, file, where).get<long>();
    const json& bbox = member(a, "bbox", json::value_t::array, file, where);
    // Within a million pixels, as the polygons: training turns box coordinates into ints.
    if (bbox.size() != 4 || !std::all_of(bbox.begin(), bbox.end(), [](const json& v) {
          return v.is_number() && std::abs(v.get<double>()) <= 1e6;
        }))
      throw Error(file, where + ": 'bbox' is not [x, y, width, height] (numbers, pixels)");
    const auto img = image_index.find(image_id);
    if (img == image_index.end())
      throw Error(file, where + ": 'image_id' " + std::to_string(image_id) + " names no image");
    // A malformed box is an error even in a class the model does not detect.
    const float x = bbox[0].get<float>(), y = bbox[1].get<float>(), w = bbox[2].get<float>(), h = bbox[3].get<float>();
    if (w < 0 || h < 0) throw Error(file, where + ": 'bbox' has a negative size");
    const auto cls = category_class.find(cat);
    if (cls == category_class.end()) continue;  // a class not detected
    DetectionSample& s = out.samples[img->second];
    s.boxes.push_back({x, y, x + w, y + h, cls->second, 1.f});
    // Polygons (a list of [x0, y0, x1, y1, ...]); RLE masks (crowds) give a box only.
    if (a.contains("segmentation") && a["segmentation"].is_array() && !a["segmentation"].empty()) {
      std::vector<std::vector<cv::Point>> polys;
      for (const auto& poly : a["segmentation"]) {
        // Every coordinate a number, and within a million pixels: the points become ints for
        // cv::fillPoly (fuzzing finding 22: an object inside a polygon escaped as json::type_error).
        if (!poly.is_array() || poly.size() < 6 || poly.size() % 2 ||
            !std::all_of(poly.begin(), poly.end(),
                         [](const json& v) { return v.is_number() && std::abs(v.get<double>()) <= 1e6; }))
          throw Error(file,
                      where + ": 'segmentation' holds a polygon that is not [x0, y0, x1, y1, ...] (numbers, pixels)");
        std::vector<cv::Point> pts;
        for (std::size_t k = 0; k + 1 < poly.size(); k += 2)
          pts.emplace_back(int(std::lround(poly[k].get<double>())), int(std::lround(poly[k + 1].get<double>())));
        polys.push_back(std::move(pts));
      }
      if (s.masks.empty()) s.masks.assign(out.classes.size(), GrayImage(s.image.width, s.image.height));
      GrayImage& m = s.masks[std::size_t(cls->second)];
      cv::Mat mat(m.height, m.width, CV_8UC1, m.data.data());
      cv::fillPoly(mat, polys, cv::Scalar(255));
    }
  }
  return out;
}

DetectionDataset read_voc_detection(const std::filesystem::path& voc_dir, const std::filesystem::path& images_dir,
                                    const std::vector<std::string>& classes) {
  if (classes.empty()) throw Error("--classes", "a VOC set needs the class names");
  if (std::error_code ec; !std::filesystem::is_directory(voc_dir, ec))
    throw Error(voc_dir.string(), "not a folder of VOC annotations");
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(voc_dir))
    if (e.path().extension() == ".xml") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  if (files.empty()) throw Error(voc_dir.string(), "holds no .xml annotation");
  DetectionDataset out;
  out.classes = classes;
  for (const auto& f : files) {
    const io::VocAnnotation a = io::read_voc(f);
    std::filesystem::path image = find_image(images_dir, a.filename);
    for (const char* ext : {".jpg", ".png"})
      if (a.filename.empty() || !is_file(image)) {
        const auto alt = images_dir / (f.stem().string() + ext);
        if (is_file(alt)) image = alt;
      }
    DetectionSample s;
    s.name = image.filename().string();
    s.image = io::read_color(image);
    for (const auto& o : a.objects)
      if (const int c = class_of(classes, o.name); c >= 0)
        s.boxes.push_back({float(o.xmin), float(o.ymin), float(o.xmax), float(o.ymax), c, 1.f});
    out.samples.push_back(std::move(s));
  }
  return out;
}

DetectionSplit split_detection_set(std::vector<DetectionSample> samples, double fraction, std::uint64_t seed) {
  if (!(fraction >= 0 && fraction < 1)) throw Error("--val-split", "must be in [0, 1)");
  const std::size_t n = samples.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::mt19937_64 rng(seed);
  std::shuffle(order.begin(), order.end(), rng);
  std::size_t k = std::size_t(std::lround(fraction * double(n)));
  if (fraction > 0 && n >= 2) k = std::clamp<std::size_t>(k, 1, n - 1);
  std::vector<bool> held_out(n, false);
  for (std::size_t i = 0; i < k; ++i) held_out[order[i]] = true;
  DetectionSplit s;
  for (std::size_t i = 0; i < n; ++i) (held_out[i] ? s.val : s.train).push_back(std::move(samples[i]));
  return s;
}

}  // namespace cropsight::nn
