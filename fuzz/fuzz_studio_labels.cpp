// The bodies of a studio label save: heads of a depth frame (POST /api/frame/N/labels,
// src/studio/pixel_runs.hpp) and shapes of an image (POST /api/image/N/labels,
// src/studio/image_shapes.hpp). Each input goes to both parsers: any bytes give heads inside the
// frame, or shapes inside the image with valid class names that the COCO, YOLO and VOC writers
// take, or an error; never a crash or an allocation beyond the bounds.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>

#include "studio/image_shapes.hpp"
#include "studio/pixel_runs.hpp"

namespace {

constexpr int kWidth = 64, kHeight = 48;

void check_heads(const std::string& body) {
  constexpr int kPixels = kWidth * kHeight;
  std::string error;
  const auto heads = cropsight::studio::parse_heads_body(body, kPixels, error);
  if (heads) {
    std::size_t total = 0;
    for (const auto& head : *heads) {
      for (int p : head)
        if (p < 0 || p >= kPixels) __builtin_trap();
      total += head.size();
    }
    if (total > 4 * std::size_t(kPixels)) __builtin_trap();
  } else if (error.empty()) {
    __builtin_trap();
  }
}

bool inside(double v, int size) { return v >= 0 && v <= size; }

void check_shapes(const std::string& body) {
  using namespace cropsight;
  std::string error;
  const auto shapes = studio::parse_shapes_body(body, kWidth, kHeight, error);
  if (!shapes) {
    if (error.empty()) __builtin_trap();
    return;
  }
  if (shapes->size() > studio::kMaxShapes) __builtin_trap();
  io::ImageLabels image{"fuzz.png", kWidth, kHeight, *shapes};
  std::vector<std::string> classes;
  for (const auto& s : *shapes) {
    if (!studio::valid_class_name(s.label)) __builtin_trap();
    if (!(s.x1 < s.x2 && s.y1 < s.y2 && inside(s.x1, kWidth) && inside(s.x2, kWidth) && inside(s.y1, kHeight) &&
          inside(s.y2, kHeight)))
      __builtin_trap();
    for (const auto& part : s.polygons) {
      if (part.size() < 3 || part.size() > studio::kMaxPolygonVertices) __builtin_trap();
      for (const auto& p : part)
        if (p.x() < s.x1 || p.x() > s.x2 || p.y() < s.y1 || p.y() > s.y2) __builtin_trap();
    }
    if (std::find(classes.begin(), classes.end(), s.label) == classes.end()) classes.push_back(s.label);
  }
  // What a save writes from them: none of the writers may throw on shapes the parser passed.
  io::coco_json({classes, {image}});
  io::yolo_text(image, classes);
  io::voc_xml(image);
  studio::shapes_json(*shapes).dump();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string body(reinterpret_cast<const char*>(data), size);
  check_heads(body);
  check_shapes(body);
  return 0;
}
