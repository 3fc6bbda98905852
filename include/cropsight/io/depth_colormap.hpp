#pragma once
// The RealSense-style colourised depth the potato paper segments (§3.5.2): a jet colour map from
// red (near) through yellow, green and cyan to blue (far), black where there is no depth. The
// simulator writes it per frame (depth_color/) and a pipeline can build the same image from metric
// depth.
#include "cropsight/core/image.hpp"

namespace cropsight::io {

/// Colour of depth `z` (m) on the map spanning [near_m, far_m] (clamped); black for z <= 0.
Rgb8 depth_color(float z, float near_m, float far_m);

/// Colourised image of `depth_m` (metres, 0 = no depth).
ColorImage colorize_depth(const Image<float>& depth_m, float near_m, float far_m);

}  // namespace cropsight::io
