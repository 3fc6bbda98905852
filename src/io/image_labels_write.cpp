// Writers of image labels (io/image_labels.hpp): COCO JSON, YOLO text, VOC XML, and the instance
// label image of one image (pixel centres inside each shape).
#include <tinyxml2.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cropsight/core/error.hpp"
#include "cropsight/io/image_labels.hpp"

namespace cropsight::io {
using nlohmann::json;

namespace image_labels_detail {

std::size_t class_index(const std::vector<std::string>& classes, const std::string& label) {
  const auto it = std::find(classes.begin(), classes.end(), label);
  if (it == classes.end()) throw Error(label, "label is not one of the classes");
  return std::size_t(it - classes.begin());
}

// Shoelace area of the polygon parts (pixels²), or the box's when there is none.
double shape_area(const LabelShape& s) {
  if (s.polygons.empty()) return (s.x2 - s.x1) * (s.y2 - s.y1);
  double area = 0.0;
  for (const auto& part : s.polygons) {
    double twice = 0.0;
    for (std::size_t i = 0; i < part.size(); ++i) {
      const auto& a = part[i];
      const auto& b = part[(i + 1) % part.size()];
      twice += a.x() * b.y() - b.x() * a.y();
    }
    area += std::abs(twice) / 2.0;
  }
  return area;
}

// Even-odd rule: a ray from (x, y) towards +x crosses the parts' edges an odd number of times.
bool inside_polygons(const std::vector<std::vector<Eigen::Vector2d>>& parts, double x, double y) {
  bool inside = false;
  for (const auto& part : parts)
    for (std::size_t i = 0, j = part.size() - 1; i < part.size(); j = i++) {
      const Eigen::Vector2d &a = part[i], &b = part[j];
      if ((a.y() > y) != (b.y() > y) && x < (b.x() - a.x()) * (y - a.y()) / (b.y() - a.y()) + a.x()) inside = !inside;
    }
  return inside;
}

std::string number(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

}  // namespace image_labels_detail

using namespace image_labels_detail;

std::string coco_json(const LabelSet& set) {
  json j{{"images", json::array()}, {"annotations", json::array()}, {"categories", json::array()}};
  for (std::size_t c = 0; c < set.classes.size(); ++c)
    j["categories"].push_back({{"id", c + 1}, {"name", set.classes[c]}});
  long ann = 0;
  for (std::size_t i = 0; i < set.images.size(); ++i) {
    const ImageLabels& im = set.images[i];
    j["images"].push_back({{"id", i + 1}, {"file_name", im.file_name}, {"width", im.width}, {"height", im.height}});
    for (const LabelShape& s : im.shapes) {
      json a{{"id", ++ann},
             {"image_id", i + 1},
             {"category_id", class_index(set.classes, s.label) + 1},
             {"bbox", {s.x1, s.y1, s.x2 - s.x1, s.y2 - s.y1}},
             {"area", shape_area(s)},
             {"iscrowd", 0}};
      if (!s.polygons.empty()) {
        a["segmentation"] = json::array();
        for (const auto& part : s.polygons) {
          json flat = json::array();
          for (const auto& p : part) flat.push_back(p.x()), flat.push_back(p.y());
          a["segmentation"].push_back(flat);
        }
      }
      j["annotations"].push_back(std::move(a));
    }
  }
  // Names come from files checked as UTF-8; replace, not throw, should one still be malformed.
  return j.dump(1, ' ', false, json::error_handler_t::replace) + "\n";
}

std::string yolo_text(const ImageLabels& image, const std::vector<std::string>& classes) {
  std::string out;
  for (const LabelShape& s : image.shapes) {
    const double w = image.width, h = image.height;
    out += std::to_string(class_index(classes, s.label)) + " " + number((s.x1 + s.x2) / 2 / w) + " " +
           number((s.y1 + s.y2) / 2 / h) + " " + number((s.x2 - s.x1) / w) + " " + number((s.y2 - s.y1) / h) + "\n";
  }
  return out;
}

std::string voc_xml(const ImageLabels& image) {
  tinyxml2::XMLDocument doc;
  auto* root = doc.NewElement("annotation");
  doc.InsertEndChild(root);
  auto add = [&](tinyxml2::XMLElement* parent, const char* name, const std::string& text) {
    auto* e = doc.NewElement(name);
    e->SetText(text.c_str());
    parent->InsertEndChild(e);
    return e;
  };
  add(root, "filename", image.file_name);
  auto* size = doc.NewElement("size");
  root->InsertEndChild(size);
  add(size, "width", std::to_string(image.width));
  add(size, "height", std::to_string(image.height));
  add(size, "depth", "3");
  for (const LabelShape& s : image.shapes) {
    auto* obj = doc.NewElement("object");
    root->InsertEndChild(obj);
    add(obj, "name", s.label);
    add(obj, "difficult", "0");
    auto* box = doc.NewElement("bndbox");
    obj->InsertEndChild(box);
    add(box, "xmin", number(s.x1));
    add(box, "ymin", number(s.y1));
    add(box, "xmax", number(s.x2));
    add(box, "ymax", number(s.y2));
  }
  tinyxml2::XMLPrinter printer;
  doc.Print(&printer);
  return printer.CStr();
}

LabelImage rasterise_instances(const ImageLabels& image, int first_id) {
  if (first_id < 1 || first_id + int(image.shapes.size()) - 1 > 65535)
    throw Error(image.file_name, "instance ids must lie in 1..65535");
  LabelImage out(image.width, image.height, 0);
  for (std::size_t k = 0; k < image.shapes.size(); ++k) {
    const LabelShape& s = image.shapes[k];
    // Pixels whose centre (u + 0.5, v + 0.5) lies in the box [x1, x2) × [y1, y2), or for a polygon
    // inside it (even-odd rule over every part; the box bounds its vertices).
    double x1 = s.x1, y1 = s.y1, x2 = s.x2, y2 = s.y2;
    if (!s.polygons.empty()) {
      x1 = y1 = std::numeric_limits<double>::infinity();
      x2 = y2 = -x1;
      for (const auto& part : s.polygons)
        for (const auto& p : part)
          x1 = std::min(x1, p.x()), y1 = std::min(y1, p.y()), x2 = std::max(x2, p.x()), y2 = std::max(y2, p.y());
    }
    // Clamped while still a double (fmin/fmax also map NaN to a bound): a coordinate far outside the
    // image must not overflow int.
    const auto column = [](double x, int size) {
      return int(std::fmin(std::fmax(std::ceil(x - 0.5), 0.0), double(size)));
    };
    const int u0 = column(x1, image.width), u1 = column(x2, image.width);
    const int v0 = column(y1, image.height), v1 = column(y2, image.height);
    for (int v = v0; v < v1; ++v)
      for (int u = u0; u < u1; ++u)
        if (s.polygons.empty() || inside_polygons(s.polygons, u + 0.5, v + 0.5))
          out.at(u, v) = std::uint16_t(first_id + int(k));
  }
  return out;
}

int frame_index_from_name(const std::string& file_name) {
  const std::string stem = std::filesystem::path(file_name).stem().string();
  std::size_t end = stem.size();
  while (end > 0 && !std::isdigit(static_cast<unsigned char>(stem[end - 1]))) --end;
  std::size_t begin = end;
  while (begin > 0 && std::isdigit(static_cast<unsigned char>(stem[begin - 1]))) --begin;
  if (begin == end || end - begin > 9) return -1;
  return std::stoi(stem.substr(begin, end - begin));
}

}  // namespace cropsight::io
