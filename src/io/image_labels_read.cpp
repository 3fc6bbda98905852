// Readers of other tools' image labels (io/image_labels.hpp): COCO and labelme through nlohmann
// JSON, CVAT XML through tinyxml2. Each checks every number it keeps and names the key or element.
#include <tinyxml2.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/image_labels.hpp"
#include "json_file.hpp"
#include "number_text.hpp"

namespace cropsight::io {
namespace fs = std::filesystem;
using nlohmann::json;

namespace image_labels_detail {

double number_at(const json& j, const std::string& file, const std::string& what) {
  if (!j.is_number() || !std::isfinite(j.get<double>())) throw Error(file, what + ": expected a finite number");
  return j.get<double>();
}

// Sets the shape's box to the bounds of its polygon parts; refuses a part of fewer than 3 vertices.
void bound_polygons(LabelShape& s, const std::string& file, const std::string& what) {
  bool first = true;
  for (const auto& part : s.polygons) {
    if (part.size() < 3) throw Error(file, what + ": a polygon needs at least 3 points");
    for (const auto& p : part) {
      s.x1 = first ? p.x() : std::min(s.x1, p.x());
      s.y1 = first ? p.y() : std::min(s.y1, p.y());
      s.x2 = first ? p.x() : std::max(s.x2, p.x());
      s.y2 = first ? p.y() : std::max(s.y2, p.y());
      first = false;
    }
  }
}

void check_box(const LabelShape& s, const std::string& file, const std::string& what) {
  for (double v : {s.x1, s.y1, s.x2, s.y2})
    if (!std::isfinite(v)) throw Error(file, what + ": coordinates must be finite");
  if (s.x2 < s.x1 || s.y2 < s.y1) throw Error(file, what + ": box with a negative width or height");
}

int positive_int(const json& j, const char* key, const std::string& file, const std::string& what) {
  if (!j.contains(key) || !j[key].is_number_integer() || j[key].get<long long>() <= 0 ||
      j[key].get<long long>() > 1000000)
    throw Error(file, what + ": '" + key + "' must be a positive integer");
  return j[key].get<int>();
}

std::string string_at(const json& j, const char* key, const std::string& file, const std::string& what) {
  if (!j.contains(key) || !j[key].is_string()) throw Error(file, what + ": '" + key + "' must be a string");
  return j[key].get<std::string>();
}

// "x1,y1;x2,y2;..." (CVAT) into vertices.
std::vector<Eigen::Vector2d> parse_cvat_points(const std::string& text, const std::string& file,
                                               const std::string& what) {
  std::vector<Eigen::Vector2d> out;
  std::stringstream ss(text);
  for (std::string pair; std::getline(ss, pair, ';');) {
    const auto comma = pair.find(',');
    const auto x = comma == std::string::npos ? std::nullopt : detail::parse_double(pair.substr(0, comma));
    const auto y = comma == std::string::npos ? std::nullopt : detail::parse_double(pair.substr(comma + 1));
    if (!x || !y || !std::isfinite(*x) || !std::isfinite(*y))
      throw Error(file, what + ": points '" + pair + "' is not 'x,y'");
    out.emplace_back(*x, *y);
  }
  return out;
}

double cvat_number(const tinyxml2::XMLElement* e, const char* name, const std::string& file, const std::string& what) {
  const char* text = e->Attribute(name);
  const auto v = text ? detail::parse_double(text) : std::nullopt;
  if (!v || !std::isfinite(*v)) throw Error(file, what + ": attribute " + name + " is missing or not a number");
  return *v;
}

// Whether `s` is well-formed UTF-8 (XML text must be; tinyxml2 does not check, and the names go on
// into JSON, which must be).
bool valid_utf8(const std::string& s) {
  for (std::size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    const int extra = c < 0x80 ? 0 : (c >> 5) == 0x6 ? 1 : (c >> 4) == 0xE ? 2 : (c >> 3) == 0x1E ? 3 : -1;
    if (extra < 0 || (extra > 0 && i + std::size_t(extra) >= s.size())) return false;
    for (int k = 1; k <= extra; ++k)
      if ((static_cast<unsigned char>(s[i + std::size_t(k)]) >> 6) != 0x2) return false;
    i += std::size_t(extra) + 1;
  }
  return true;
}

// A text attribute of a CVAT element: present, well-formed UTF-8.
std::string cvat_text(const tinyxml2::XMLElement* e, const char* name, const std::string& file,
                      const std::string& what) {
  const char* text = e->Attribute(name);
  if (!text || !*text) throw Error(file, what + ": no " + name + " attribute");
  if (!valid_utf8(text)) throw Error(file, what + ": attribute " + name + " is not UTF-8");
  return text;
}

void note_class(LabelSet& set, const std::string& label) {
  if (std::find(set.classes.begin(), set.classes.end(), label) == set.classes.end()) set.classes.push_back(label);
}

// One COCO annotation into its image's shapes.
void add_coco_annotation(const json& a, const std::string& file, const std::string& what,
                         const std::map<long long, std::string>& categories, LabelSet& set,
                         const std::map<long long, std::size_t>& image_at) {
  if (!a.is_object() || !a.contains("image_id") || !a["image_id"].is_number_integer())
    throw Error(file, what + ": 'image_id' must be an integer");
  if (!a.contains("category_id") || !a["category_id"].is_number_integer())
    throw Error(file, what + ": 'category_id' must be an integer");
  const auto img = image_at.find(a["image_id"].get<long long>());
  if (img == image_at.end()) throw Error(file, what + ": image_id names no image of 'images'");
  const auto cat = categories.find(a["category_id"].get<long long>());
  if (cat == categories.end()) throw Error(file, what + ": category_id names no category of 'categories'");
  LabelShape s;
  s.label = cat->second;
  if (a.contains("segmentation") && a["segmentation"].is_array()) {
    for (const auto& part : a["segmentation"]) {
      if (!part.is_array() || part.size() % 2 != 0) throw Error(file, what + ": a polygon is [x, y, x, y, ...]");
      std::vector<Eigen::Vector2d> poly;
      for (std::size_t k = 0; k < part.size(); k += 2)
        poly.emplace_back(number_at(part[k], file, what + " segmentation"),
                          number_at(part[k + 1], file, what + " segmentation"));
      s.polygons.push_back(std::move(poly));
    }
  }
  if (!s.polygons.empty()) {
    bound_polygons(s, file, what);
  } else {  // a box, or an RLE mask of which only the box is kept
    if (!a.contains("bbox") || !a["bbox"].is_array() || a["bbox"].size() != 4)
      throw Error(file, what + ": no polygon and no 'bbox' [x, y, w, h]");
    s.x1 = number_at(a["bbox"][0], file, what + " bbox");
    s.y1 = number_at(a["bbox"][1], file, what + " bbox");
    s.x2 = s.x1 + number_at(a["bbox"][2], file, what + " bbox");
    s.y2 = s.y1 + number_at(a["bbox"][3], file, what + " bbox");
  }
  check_box(s, file, what);
  set.images[img->second].shapes.push_back(std::move(s));
}

}  // namespace image_labels_detail

using namespace image_labels_detail;

LabelSet read_coco_labels(const fs::path& path) {
  const std::string file = path.string();
  const json j = detail::read_json_file(path);
  for (const char* key : {"images", "annotations", "categories"})
    if (!j.is_object() || !j.contains(key) || !j[key].is_array())
      throw Error(file, std::string("'") + key + "' must be an array (a COCO instances file)");
  LabelSet set;
  std::map<long long, std::string> categories;
  for (std::size_t k = 0; k < j["categories"].size(); ++k) {
    const json& c = j["categories"][k];
    const std::string what = "categories[" + std::to_string(k) + "]";
    if (!c.is_object() || !c.contains("id") || !c["id"].is_number_integer())
      throw Error(file, what + ": 'id' must be an integer");
    categories[c["id"].get<long long>()] = string_at(c, "name", file, what);
  }
  for (const auto& [id, name] : categories) note_class(set, name);
  std::map<long long, std::size_t> image_at;
  for (std::size_t k = 0; k < j["images"].size(); ++k) {
    const json& im = j["images"][k];
    const std::string what = "images[" + std::to_string(k) + "]";
    if (!im.is_object() || !im.contains("id") || !im["id"].is_number_integer())
      throw Error(file, what + ": 'id' must be an integer");
    if (!image_at.emplace(im["id"].get<long long>(), set.images.size()).second)
      throw Error(file, what + ": id " + std::to_string(im["id"].get<long long>()) + " is used twice");
    set.images.push_back({string_at(im, "file_name", file, what),
                          positive_int(im, "width", file, what),
                          positive_int(im, "height", file, what),
                          {}});
  }
  for (std::size_t k = 0; k < j["annotations"].size(); ++k)
    add_coco_annotation(j["annotations"][k], file, "annotations[" + std::to_string(k) + "]", categories, set, image_at);
  return set;
}

LabelSet read_labelme_labels(const fs::path& dir) {
  if (!fs::is_directory(dir)) throw Error(dir.string(), "not a folder of labelme JSON files");
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && e.path().extension() == ".json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  if (files.empty()) throw Error(dir.string(), "holds no labelme .json file");
  LabelSet set;
  for (const fs::path& path : files) {
    const std::string file = path.string();
    const json j = detail::read_json_file(path);
    if (!j.is_object() || !j.contains("shapes") || !j["shapes"].is_array())
      throw Error(file, "'shapes' must be an array (a labelme file)");
    ImageLabels image{string_at(j, "imagePath", file, "labelme"),
                      positive_int(j, "imageWidth", file, "labelme"),
                      positive_int(j, "imageHeight", file, "labelme"),
                      {}};
    for (std::size_t k = 0; k < j["shapes"].size(); ++k) {
      const json& sh = j["shapes"][k];
      const std::string what = "shapes[" + std::to_string(k) + "]";
      LabelShape s;
      s.label = string_at(sh, "label", file, what);
      const std::string type = sh.contains("shape_type") && sh["shape_type"].is_string() ? sh["shape_type"] : "polygon";
      if (!sh.contains("points") || !sh["points"].is_array()) throw Error(file, what + ": 'points' must be an array");
      std::vector<Eigen::Vector2d> pts;
      for (const auto& p : sh["points"]) {
        if (!p.is_array() || p.size() != 2) throw Error(file, what + ": a point is [x, y]");
        pts.emplace_back(number_at(p[0], file, what), number_at(p[1], file, what));
      }
      if (type == "rectangle") {
        if (pts.size() != 2) throw Error(file, what + ": a rectangle has 2 points");
        s.x1 = std::min(pts[0].x(), pts[1].x()), s.x2 = std::max(pts[0].x(), pts[1].x());
        s.y1 = std::min(pts[0].y(), pts[1].y()), s.y2 = std::max(pts[0].y(), pts[1].y());
      } else if (type == "polygon") {
        s.polygons.push_back(std::move(pts));
        bound_polygons(s, file, what);
      } else {
        throw Error(file, what + ": shape_type '" + type + "' is not imported (rectangle or polygon)");
      }
      check_box(s, file, what);
      note_class(set, s.label);
      image.shapes.push_back(std::move(s));
    }
    set.images.push_back(std::move(image));
  }
  return set;
}

LabelSet read_cvat_labels(const fs::path& path) {
  const std::string file = path.string();
  tinyxml2::XMLDocument doc;
  if (doc.LoadFile(file.c_str()) != tinyxml2::XML_SUCCESS)
    throw Error(file, std::string("not readable XML: ") + (doc.ErrorStr() ? doc.ErrorStr() : "?"));
  const tinyxml2::XMLElement* root = doc.RootElement();
  if (!root || std::string(root->Name()) != "annotations")
    throw Error(file, "root element is not <annotations> (CVAT for images 1.1)");
  LabelSet set;
  int index = 0;
  for (const auto* im = root->FirstChildElement("image"); im; im = im->NextSiblingElement("image"), ++index) {
    const std::string what = "image " + std::to_string(index);
    const double width = cvat_number(im, "width", file, what), height = cvat_number(im, "height", file, what);
    if (!(width >= 1 && width <= 1e6 && height >= 1 && height <= 1e6) || width != std::floor(width) ||
        height != std::floor(height))
      throw Error(file, what + ": width and height must be whole numbers of pixels in 1..1000000");
    ImageLabels image{cvat_text(im, "name", file, what), int(width), int(height), {}};
    for (const auto* e = im->FirstChildElement(); e; e = e->NextSiblingElement()) {
      const std::string kind = e->Name(), at = what + " <" + kind + ">";
      if (kind != "box" && kind != "polygon") continue;  // tags, points, masks: not shapes we import
      LabelShape s;
      s.label = cvat_text(e, "label", file, at);
      if (kind == "box") {
        s.x1 = cvat_number(e, "xtl", file, at), s.y1 = cvat_number(e, "ytl", file, at);
        s.x2 = cvat_number(e, "xbr", file, at), s.y2 = cvat_number(e, "ybr", file, at);
      } else {
        s.polygons.push_back(parse_cvat_points(e->Attribute("points") ? e->Attribute("points") : "", file, at));
        bound_polygons(s, file, at);
      }
      check_box(s, file, at);
      note_class(set, s.label);
      image.shapes.push_back(std::move(s));
    }
    set.images.push_back(std::move(image));
  }
  if (set.images.empty()) throw Error(file, "holds no <image> (CVAT for images 1.1; video tracks are not imported)");
  return set;
}

}  // namespace cropsight::io
