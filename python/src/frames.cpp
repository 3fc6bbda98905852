#include "frames.hpp"

#include "arrays.hpp"

namespace cropsight::python {

namespace {
void check_size(const std::string& name, int width, int height, const CameraIntrinsics& camera) {
  if (width != camera.width || height != camera.height)
    throw py::value_error(name + ": shape (" + std::to_string(height) + ", " + std::to_string(width) +
                          ") differs from the camera's image size (" + std::to_string(camera.height) + ", " +
                          std::to_string(camera.width) + ")");
}
}  // namespace

RgbdFrame frame_from_arrays(const py::object& depth, const py::object& color, const CameraIntrinsics& camera, int index,
                            double timestamp, const py::object& pose) {
  camera.validate("camera");
  RgbdFrame f;
  f.index = index;
  f.timestamp = timestamp;
  f.camera = camera;
  if (!depth.is_none()) {
    f.depth = depth_from_array(depth, "depth");
    check_size("depth", f.depth.width, f.depth.height, camera);
  }
  if (!color.is_none()) {
    f.color = color_from_array(color, "color");
    check_size("color", f.color.width, f.color.height, camera);
  }
  if (depth.is_none() && color.is_none()) throw py::value_error("depth, color: a frame needs at least one of them");
  if (!pose.is_none()) f.camera_position = vector3_from(pose, "pose");
  return f;
}

const RgbdFrame& frame_argument(const py::object& frame, const py::object& depth, const py::object& color,
                                const py::object& camera, RgbdFrame& storage) {
  if (!frame.is_none()) {
    if (!depth.is_none() || !color.is_none() || !camera.is_none())
      throw py::type_error("process: give either a frame or depth=/color=/camera=, not both");
    if (!py::isinstance<RgbdFrame>(frame))
      throw py::type_error("frame: expected a cropsight.Frame, got " + describe(frame));
    return frame.cast<const RgbdFrame&>();
  }
  if (camera.is_none())
    throw py::type_error("camera: process(depth=..., color=...) needs camera=cropsight.Camera(...)");
  if (!py::isinstance<CameraIntrinsics>(camera))
    throw py::type_error("camera: expected a cropsight.Camera, got " + describe(camera));
  storage = frame_from_arrays(depth, color, camera.cast<const CameraIntrinsics&>(), 0, 0.0, py::none());
  return storage;
}

}  // namespace cropsight::python
