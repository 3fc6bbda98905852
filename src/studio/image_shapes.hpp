#pragma once
// Boxes and polygons on the wire: what the image page sends when it saves an image's labels and
// what the server answers with (JSON). A shape is {"label": NAME, "box": [x1, y1, x2, y2]} or
// {"label": NAME, "polygon": [x, y, x, y, ...]}, in image pixels with continuous corners (a box
// covers x1 <= x < x2); a polygon's box is the bounds of its vertices.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cropsight/io/image_labels.hpp"

namespace cropsight::studio {

/// Bounds of one save: a body that passes them holds at most this many shapes, vertices per
/// polygon and bytes per class name (a few kilobytes of JSON cannot make the server hold more).
inline constexpr std::size_t kMaxShapes = 2000;
inline constexpr std::size_t kMaxPolygonVertices = 2000;
inline constexpr std::size_t kMaxLabelBytes = 64;

/// Whether `label` may name a class: 1..kMaxLabelBytes bytes, no control character (YOLO's
/// classes.txt holds one per line), no leading or trailing space.
bool valid_class_name(const std::string& label);

/// The shapes of a save's body, {"shapes": [shape, ...]}, for an image of `width` × `height`
/// pixels: coordinates finite, clamped into the image, boxes not empty after clamping, polygons
/// of 3..kMaxPolygonVertices vertices. Nothing (with `error` set) when the body is not that JSON
/// or a shape breaks a rule.
std::optional<std::vector<io::LabelShape>> parse_shapes_body(const std::string& body, int width, int height,
                                                             std::string& error);

/// `shapes` in the wire form (a polygon of several parts sends its first part only: the page
/// draws one outline per shape).
nlohmann::json shapes_json(const std::vector<io::LabelShape>& shapes);

}  // namespace cropsight::studio
