#pragma once
// Overlay figures of potato detections (the CLI's --overlay): boxes and scores drawn in place.
#include <vector>

#include "cropsight/core/detection2d.hpp"
#include "cropsight/core/image.hpp"

namespace cropsight::pipeline::potato {

/// Draws each box (green, 2 px, inside [x1, x2) x [y1, y2)) and its score above it into `img`.
void draw_detections(ColorImage& img, const std::vector<Detection2D>& dets);

}  // namespace cropsight::pipeline::potato
