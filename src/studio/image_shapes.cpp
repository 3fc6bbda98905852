// Boxes and polygons on the wire (image_shapes.hpp).
#include "studio/image_shapes.hpp"

#include <algorithm>
#include <cmath>

namespace cropsight::studio {

namespace {

// A finite coordinate clamped into [0, size]; nothing for NaN, infinities and non-numbers.
std::optional<double> coordinate(const nlohmann::json& v, int size) {
  if (!v.is_number()) return std::nullopt;
  const double x = v.get<double>();
  if (!std::isfinite(x)) return std::nullopt;
  return std::clamp(x, 0.0, double(size));
}

// The polygon of a flat [x, y, ...] array; its box becomes the shape's box.
bool read_polygon(const nlohmann::json& flat, int width, int height, io::LabelShape& s, std::string& error) {
  if (!flat.is_array() || flat.size() % 2 != 0 || flat.size() < 6 || flat.size() > 2 * kMaxPolygonVertices) {
    error = "a polygon is [x, y, x, y, ...] with 3 to " + std::to_string(kMaxPolygonVertices) + " vertices";
    return false;
  }
  std::vector<Eigen::Vector2d> part;
  for (std::size_t k = 0; k < flat.size(); k += 2) {
    const auto x = coordinate(flat[k], width), y = coordinate(flat[k + 1], height);
    if (!x || !y) {
      error = "polygon vertices must be finite numbers";
      return false;
    }
    part.emplace_back(*x, *y);
  }
  s.x1 = s.x2 = part[0].x();
  s.y1 = s.y2 = part[0].y();
  for (const auto& p : part) {
    s.x1 = std::min(s.x1, p.x()), s.x2 = std::max(s.x2, p.x());
    s.y1 = std::min(s.y1, p.y()), s.y2 = std::max(s.y2, p.y());
  }
  if (s.x2 <= s.x1 || s.y2 <= s.y1) {
    error = "a polygon must enclose an area inside the image";
    return false;
  }
  s.polygons.push_back(std::move(part));
  return true;
}

bool read_box(const nlohmann::json& box, int width, int height, io::LabelShape& s, std::string& error) {
  if (!box.is_array() || box.size() != 4) {
    error = "a box is [x1, y1, x2, y2]";
    return false;
  }
  const auto x1 = coordinate(box[0], width), y1 = coordinate(box[1], height);
  const auto x2 = coordinate(box[2], width), y2 = coordinate(box[3], height);
  if (!x1 || !y1 || !x2 || !y2) {
    error = "box corners must be finite numbers";
    return false;
  }
  if (*x2 <= *x1 || *y2 <= *y1) {
    error = "a box needs x2 > x1 and y2 > y1 inside the image";
    return false;
  }
  s.x1 = *x1, s.y1 = *y1, s.x2 = *x2, s.y2 = *y2;
  return true;
}

std::optional<io::LabelShape> read_shape(const nlohmann::json& j, int width, int height, std::string& error) {
  if (!j.is_object() || !j.contains("label") || !j["label"].is_string()) {
    error = "a shape is {\"label\": NAME, \"box\" or \"polygon\": [...]}";
    return std::nullopt;
  }
  io::LabelShape s;
  s.label = j["label"].get<std::string>();
  if (!valid_class_name(s.label)) {
    error = "a class name has 1 to " + std::to_string(kMaxLabelBytes) +
            " characters, no control characters and no space at either end";
    return std::nullopt;
  }
  const bool box = j.contains("box"), polygon = j.contains("polygon");
  if (box == polygon) {
    error = "a shape has either a \"box\" or a \"polygon\"";
    return std::nullopt;
  }
  const bool ok =
      box ? read_box(j["box"], width, height, s, error) : read_polygon(j["polygon"], width, height, s, error);
  if (!ok) return std::nullopt;
  return s;
}

}  // namespace

bool valid_class_name(const std::string& label) {
  if (label.empty() || label.size() > kMaxLabelBytes || label.front() == ' ' || label.back() == ' ') return false;
  return std::none_of(label.begin(), label.end(), [](char c) {
    const auto u = static_cast<unsigned char>(c);
    return u < 0x20 || u == 0x7f;
  });
}

std::optional<std::vector<io::LabelShape>> parse_shapes_body(const std::string& body, int width, int height,
                                                             std::string& error) {
  const nlohmann::json j = nlohmann::json::parse(body, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object() || !j.contains("shapes") || !j["shapes"].is_array()) {
    error = "expected {\"shapes\": [{\"label\": NAME, \"box\": [x1, y1, x2, y2]} or {..., \"polygon\": [x, y, ...]}]}";
    return std::nullopt;
  }
  if (j["shapes"].size() > kMaxShapes) {
    error = "more than " + std::to_string(kMaxShapes) + " shapes on one image";
    return std::nullopt;
  }
  std::vector<io::LabelShape> shapes;
  for (const auto& item : j["shapes"]) {
    auto s = read_shape(item, width, height, error);
    if (!s) return std::nullopt;
    shapes.push_back(std::move(*s));
  }
  return shapes;
}

nlohmann::json shapes_json(const std::vector<io::LabelShape>& shapes) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& s : shapes) {
    nlohmann::json j{{"label", s.label}};
    if (s.polygons.empty()) {
      j["box"] = {s.x1, s.y1, s.x2, s.y2};
    } else {
      nlohmann::json flat = nlohmann::json::array();
      for (const auto& p : s.polygons.front()) flat.push_back(p.x()), flat.push_back(p.y());
      j["polygon"] = std::move(flat);
    }
    out.push_back(std::move(j));
  }
  return out;
}

}  // namespace cropsight::studio
