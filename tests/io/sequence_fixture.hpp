#pragma once
// A small synthetic sequence written with SequenceWriter, for io/report/CLI tests. Generated in
// the test itself (no committed data): 16x12 pixels, a tilted plane with holes, two labelled
// discs, colour, poses and ground truth.
#include <filesystem>

#include "cropsight/io/sequence.hpp"

namespace cropsight::testing {

inline CameraIntrinsics fixture_camera(int w = 16, int h = 12) {
  CameraIntrinsics c = CameraIntrinsics::from_fov(w, h, 1.2322, 1.0472);  // ~70.6° x 60°
  c.depth_scale = 0.001;
  c.sensor = "fixture";
  return c;
}

inline RgbdFrame fixture_frame(int index, const CameraIntrinsics& cam, bool color = true, bool labels = true,
                               bool pose = true) {
  RgbdFrame f;
  f.index = index;
  f.camera = cam;
  f.timestamp = 0.25 * index;
  f.depth = DepthImage(cam.width, cam.height);
  if (color) f.color = ColorImage(cam.width, cam.height);
  if (labels) f.labels = LabelImage(cam.width, cam.height);
  for (int v = 0; v < cam.height; ++v) {
    for (int u = 0; u < cam.width; ++u) {
      // Holes on a diagonal (no return), otherwise a plane 1.2-1.3 m away.
      const bool hole = (u + v + index) % 7 == 0;
      f.depth.at(u, v) = hole ? 0 : std::uint16_t(1200 + 5 * u + 3 * v + index);
      if (color) f.color.at(u, v) = Rgb8{std::uint8_t(10 * u), std::uint8_t(20 * v), std::uint8_t(7 * index)};
      if (labels) {
        const int du = u - 4 - index % 3, dv = v - 4;
        const int du2 = u - 11, dv2 = v - 7;
        if (du * du + dv * dv <= 6) f.labels.at(u, v) = 1;
        if (du2 * du2 + dv2 * dv2 <= 4) f.labels.at(u, v) = 2;
      }
    }
  }
  if (pose) f.camera_position = Eigen::Vector3d(0.3 * 0.25 * index, 0.0, 1.25);
  return f;
}

inline io::GroundTruth fixture_truth() {
  io::GroundTruth t;
  io::InstanceTruth a;
  a.id = 1;
  a.position = {0.1, -0.05, 0.0};
  a.diameter_mm = 120.5;
  a.extra["height_m"] = 0.55;
  io::InstanceTruth b;
  b.id = 2;
  b.position = {0.4, 0.1, 0.01};
  b.diameter_mm = 88.0;
  t.instances = {a, b};
  t.attributes["variety"] = "fixture";
  t.attributes["seed"] = "7";
  return t;
}

/// Writes a complete fixture sequence of `frames` frames to `dir`.
inline void write_fixture_sequence(const std::filesystem::path& dir, int frames = 3, bool color = true,
                                   bool labels = true, bool pose = true, bool truth = true) {
  const CameraIntrinsics cam = fixture_camera();
  io::SequenceWriter w(dir, cam);
  for (int i = 0; i < frames; ++i) w.write(fixture_frame(i, cam, color, labels, pose));
  if (truth) w.set_groundtruth(fixture_truth());
  w.finish();
}

}  // namespace cropsight::testing
