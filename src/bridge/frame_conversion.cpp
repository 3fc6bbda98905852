#include "frame_conversion.hpp"

#include "cropsight/core/error.hpp"

namespace cropsight::bridge {

ColorImage color_from_rgb(const std::vector<std::uint8_t>& rgb, int width, int height) {
  ColorImage c(width, height);
  for (std::size_t i = 0; i < c.size(); ++i) c.data[i] = {rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]};
  return c;
}

std::vector<std::uint8_t> rgb_from_color(const ColorImage& color) {
  std::vector<std::uint8_t> rgb(3 * color.size());
  for (std::size_t i = 0; i < color.size(); ++i) {
    rgb[3 * i] = color.data[i].r;
    rgb[3 * i + 1] = color.data[i].g;
    rgb[3 * i + 2] = color.data[i].b;
  }
  return rgb;
}

CameraIntrinsics to_intrinsics(const CameraModel& c) {
  CameraIntrinsics k;
  k.width = c.width;
  k.height = c.height;
  k.fx = c.fx;
  k.fy = c.fy;
  k.cx = c.cx;
  k.cy = c.cy;
  k.depth_scale = c.depth_scale;
  k.distortion = c.distortion;
  k.sensor = c.sensor;
  return k;
}

CameraModel to_camera_model(const CameraIntrinsics& k) {
  CameraModel c;
  c.width = k.width;
  c.height = k.height;
  c.fx = k.fx;
  c.fy = k.fy;
  c.cx = k.cx;
  c.cy = k.cy;
  c.depth_scale = k.depth_scale;
  c.distortion = k.distortion;
  c.sensor = k.sensor;
  return c;
}

RgbdFrame to_rgbd_frame(const FrameBuffers& f) {
  const std::string where = "frame " + std::to_string(f.index);
  RgbdFrame r;
  r.index = f.index;
  r.timestamp = f.timestamp;
  r.camera = to_intrinsics(f.camera);
  r.camera.validate(where + " camera");
  const std::size_t pixels = std::size_t(f.camera.width) * std::size_t(f.camera.height);
  if (!f.depth.empty()) {
    if (f.depth.size() != pixels)
      throw Error(where, "depth has " + std::to_string(f.depth.size()) + " pixels, the camera " +
                             std::to_string(f.camera.width) + "x" + std::to_string(f.camera.height));
    r.depth.width = f.camera.width;
    r.depth.height = f.camera.height;
    r.depth.data = f.depth;
  }
  if (!f.rgb.empty()) {
    if (f.rgb.size() != 3 * pixels)
      throw Error(where, "colour has " + std::to_string(f.rgb.size() / 3) + " pixels, the camera " +
                             std::to_string(f.camera.width) + "x" + std::to_string(f.camera.height));
    r.color = color_from_rgb(f.rgb, f.camera.width, f.camera.height);
  }
  if (f.has_camera_position)
    r.camera_position = Eigen::Vector3d(f.camera_position[0], f.camera_position[1], f.camera_position[2]);
  return r;
}

FrameBuffers to_frame_buffers(const RgbdFrame& r) {
  FrameBuffers f;
  f.index = r.index;
  f.timestamp = r.timestamp;
  f.camera = to_camera_model(r.camera);
  f.depth = r.depth.data;
  if (!r.color.empty()) f.rgb = rgb_from_color(r.color);
  if (r.camera_position) {
    f.has_camera_position = true;
    for (int k = 0; k < 3; ++k) f.camera_position[k] = (*r.camera_position)[k];
  }
  return f;
}

}  // namespace cropsight::bridge
