#pragma once
// Overlay figures of potato detections (the CLI's --overlay): boxes, scores and length axes drawn
// in place.
#include <optional>
#include <vector>

#include "cropsight/core/detection2d.hpp"
#include "cropsight/core/image.hpp"

namespace cropsight::pipeline::potato {

/// Draws each box (green, 2 px, inside [x1, x2) x [y1, y2)) and its score above it into `img`;
/// where `angles_rad` has a value for the box (same order; may be shorter or empty), its length axis
/// as a red line through the box centre (radians, counter-clockwise from the image x axis).
void draw_detections(ColorImage& img, const std::vector<Detection2D>& dets,
                     const std::vector<std::optional<double>>& angles_rad = {});

}  // namespace cropsight::pipeline::potato
