#include "frame_conversion.hpp"

#include "cropsight/core/error.hpp"

namespace cropsight::bridge {

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
    r.color = ColorImage(f.camera.width, f.camera.height);
    for (std::size_t i = 0; i < pixels; ++i) r.color.data[i] = {f.rgb[3 * i], f.rgb[3 * i + 1], f.rgb[3 * i + 2]};
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
  if (!r.color.empty()) {
    f.rgb.resize(3 * r.color.size());
    for (std::size_t i = 0; i < r.color.size(); ++i) {
      f.rgb[3 * i] = r.color.data[i].r;
      f.rgb[3 * i + 1] = r.color.data[i].g;
      f.rgb[3 * i + 2] = r.color.data[i].b;
    }
  }
  if (r.camera_position) {
    f.has_camera_position = true;
    for (int k = 0; k < 3; ++k) f.camera_position[k] = (*r.camera_position)[k];
  }
  return f;
}

}  // namespace cropsight::bridge
