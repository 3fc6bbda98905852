#pragma once
// A small synthetic RGB-D frame of a vine for the grape pipeline's tests (library and CLI): a
// wall at 1.5 m, bunch A (a purple half-sphere at ~0.8 m) hanging from its peduncle (a brown
// vertical rod), and bunches B and C, whose boxes overlap (one merged ROI), with no peduncle box.
// The boxes come with the frame, as the COCO categories of the dataset (1 bunch, 2 peduncle).
#include <cmath>
#include <cstdint>
#include <vector>

#include "cropsight/core/rgbd_frame.hpp"
#include "cropsight/pipeline/grape/roi.hpp"

namespace cropsight::testing {

struct GrapeTestFrame {
  RgbdFrame frame;
  std::vector<pipeline::grape::Detection> boxes;
};

inline GrapeTestFrame grape_test_frame() {
  GrapeTestFrame t;
  CameraIntrinsics& cam = t.frame.camera;
  cam.width = 160, cam.height = 120;
  cam.fx = cam.fy = 150, cam.cx = 80, cam.cy = 60;
  cam.depth_scale = 0.001;
  t.frame.depth = DepthImage(160, 120, 1500);
  t.frame.color = ColorImage(160, 120, Rgb8{60, 140, 50});
  auto blob = [&](int cu, int cv, int r, std::uint16_t z, Rgb8 c) {
    for (int v = cv - r; v <= cv + r; ++v)
      for (int u = cu - r; u <= cu + r; ++u) {
        const int d2 = (u - cu) * (u - cu) + (v - cv) * (v - cv);
        if (d2 > r * r) continue;
        // A bulge toward the camera, 5 depth units (mm) per pixel of the sphere's height.
        t.frame.depth.at(u, v) = std::uint16_t(z - int(std::sqrt(double(r * r - d2)) * 5));
        t.frame.color.at(u, v) = c;
      }
  };
  blob(80, 75, 20, 800, Rgb8{90, 30, 110});  // bunch A
  for (int v = 35; v < 55; ++v)              // A's peduncle, above it
    for (int u = 78; u <= 81; ++u) t.frame.depth.at(u, v) = 780, t.frame.color.at(u, v) = Rgb8{120, 90, 40};
  blob(130, 80, 10, 900, Rgb8{90, 30, 110});  // bunch B
  blob(145, 90, 8, 900, Rgb8{90, 30, 110});   // bunch C, overlapping B's box
  t.boxes = {{{60, 55, 41, 41}, 1, 0.9f, 0},
             {{76, 33, 8, 22}, 2, 0.8f, 1},
             {{120, 70, 21, 21}, 1, 0.9f, 2},
             {{137, 82, 17, 17}, 1, 0.7f, 3}};
  return t;
}

}  // namespace cropsight::testing
