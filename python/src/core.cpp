// cropsight.Camera, cropsight.Frame, cropsight.Sequence / read_sequence (io/sequence.hpp).
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cstring>
#include <memory>

#include "arrays.hpp"
#include "bindings.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/sequence.hpp"
#include "frames.hpp"

namespace cropsight::python {

namespace {

std::string camera_repr(const CameraIntrinsics& c) {
  return "Camera(width=" + std::to_string(c.width) + ", height=" + std::to_string(c.height) +
         ", fx=" + std::string(py::repr(py::float_(c.fx))) + ", fy=" + std::string(py::repr(py::float_(c.fy))) +
         ", cx=" + std::string(py::repr(py::float_(c.cx))) + ", cy=" + std::string(py::repr(py::float_(c.cy))) +
         ", depth_scale=" + std::string(py::repr(py::float_(c.depth_scale))) + ")";
}

void bind_camera(py::module_& m) {
  py::class_<CameraIntrinsics>(m, "Camera",
                               "Pinhole intrinsics of the depth image (colour is registered to depth). Camera frame: x "
                               "right, y down, z forward, metres; pixel (u, v) = (column, row). A plain value: copy "
                               "freely, share between threads read-only.")
      .def(py::init([](int width, int height, double fx, double fy, double cx, double cy, double depth_scale) {
             CameraIntrinsics c;
             c.width = width, c.height = height, c.fx = fx, c.fy = fy, c.cx = cx, c.cy = cy,
             c.depth_scale = depth_scale;
             return c;
           }),
           py::kw_only(), py::arg("width"), py::arg("height"), py::arg("fx"), py::arg("fy"), py::arg("cx"),
           py::arg("cy"), py::arg("depth_scale") = 0.001,
           "Sizes in pixels, focal lengths and principal point in pixels, depth_scale in metres per raw depth unit.")
      .def_readwrite("width", &CameraIntrinsics::width, "pixels")
      .def_readwrite("height", &CameraIntrinsics::height, "pixels")
      .def_readwrite("fx", &CameraIntrinsics::fx, "focal length, pixels")
      .def_readwrite("fy", &CameraIntrinsics::fy, "focal length, pixels")
      .def_readwrite("cx", &CameraIntrinsics::cx, "principal point, pixels")
      .def_readwrite("cy", &CameraIntrinsics::cy, "principal point, pixels")
      .def_readwrite("depth_scale", &CameraIntrinsics::depth_scale, "metres per raw depth unit")
      .def_readwrite("distortion", &CameraIntrinsics::distortion, "OpenCV-order coefficients (k1 k2 p1 p2 [k3...])")
      .def_readwrite("sensor", &CameraIntrinsics::sensor, "free text, e.g. 'kinect-v2'")
      .def(
          "validate", [](const CameraIntrinsics& c) { c.validate("camera"); },
          "Raises cropsight.Error when a value is out of range (NaN, non-positive focal length, ...).")
      .def("__repr__", &camera_repr);
}

void bind_frame(py::module_& m) {
  py::class_<RgbdFrame, std::shared_ptr<RgbdFrame>>(
      m, "Frame",
      "One RGB-D frame. depth: H×W uint16 raw units (metres = value * camera.depth_scale, 0 = no return); "
      "color: H×W×3 uint8 RGB or None; camera: cropsight.Camera; index; timestamp (s); pose: the camera "
      "position in the field frame (3 floats, m) or None. The arrays are read-only views on the frame (no "
      "copy). Immutable from Python: share between threads freely.")
      .def(py::init([](const py::object& depth, const py::object& color, const CameraIntrinsics& camera, int index,
                       double timestamp, const py::object& pose) {
             return frame_from_arrays(depth, color, camera, index, timestamp, pose);
           }),
           py::kw_only(), py::arg("depth") = py::none(), py::arg("color") = py::none(), py::arg("camera"),
           py::arg("index") = 0, py::arg("timestamp") = 0.0, py::arg("pose") = py::none(),
           "Copies the arrays once into the library's images. TypeError for a wrong dtype, ValueError for a "
           "wrong shape, cropsight.Error for a camera out of range.")
      .def_property_readonly("depth",
                             [](py::object self) -> py::object {
                               const auto& f = self.cast<const RgbdFrame&>();
                               return f.depth.empty() ? py::object(py::none()) : py::object(image_view(f.depth, self));
                             })
      .def_property_readonly("color",
                             [](py::object self) { return color_view(self.cast<const RgbdFrame&>().color, self); })
      .def_property_readonly(
          "labels",
          [](py::object self) -> py::object {
            const auto& f = self.cast<const RgbdFrame&>();
            return f.labels.empty() ? py::object(py::none()) : py::object(image_view(f.labels, self));
          },
          "H×W uint16 ground-truth instance ids (0 = none), or None")
      .def_property_readonly("camera", [](const RgbdFrame& f) { return f.camera; })
      .def_property_readonly("index", [](const RgbdFrame& f) { return f.index; })
      .def_property_readonly("timestamp", [](const RgbdFrame& f) { return f.timestamp; })
      .def_property_readonly("pose",
                             [](const RgbdFrame& f) -> py::object {
                               return f.camera_position ? py::object(vector_array(*f.camera_position))
                                                        : py::object(py::none());
                             })
      .def("__repr__", [](const RgbdFrame& f) {
        return "Frame(index=" + std::to_string(f.index) + ", " + std::to_string(f.camera.width) + "x" +
               std::to_string(f.camera.height) + (f.color.empty() ? "" : ", color") +
               (f.labels.empty() ? "" : ", labels") + (f.camera_position ? ", pose" : "") + ")";
      });
}

void bind_sequence(py::module_& m) {
  py::class_<io::SequenceReader>(
      m, "Sequence",
      "An RGB-D sequence folder (docs/formats.md), opened by cropsight.read_sequence. len(seq), seq[i] "
      "(negative i counts from the end), iteration. Each frame is read from disk when asked for, with the GIL "
      "released. Not thread-safe: one Sequence per thread.")
      .def("__len__", &io::SequenceReader::size)
      .def("__getitem__",
           [](const io::SequenceReader& r, int i) {
             const int n = r.size();
             if (i < -n || i >= n)
               throw py::index_error("frame " + std::to_string(i) + " of a sequence of " + std::to_string(n));
             const int index = i < 0 ? i + n : i;
             py::gil_scoped_release free;
             return std::make_shared<RgbdFrame>(r.read(index));
           })
      .def_property_readonly("camera", [](const io::SequenceReader& r) { return r.info().camera; })
      .def_property_readonly("path", [](const io::SequenceReader& r) { return r.info().dir; })
      .def_property_readonly("has_color", [](const io::SequenceReader& r) { return r.info().has_color; })
      .def_property_readonly("has_labels", [](const io::SequenceReader& r) { return r.info().has_labels; })
      .def_property_readonly("has_poses", [](const io::SequenceReader& r) { return r.info().has_poses; })
      .def("__repr__", [](const io::SequenceReader& r) {
        return "Sequence('" + r.info().dir.string() + "', " + std::to_string(r.size()) + " frames)";
      });
  m.def(
      "read_sequence", [](const std::filesystem::path& dir) { return io::SequenceReader(dir); }, py::arg("path"),
      "Opens a sequence folder and checks its layout (frames are read when indexed). Raises cropsight.Error "
      "naming the file for a missing or broken one.");
}

void bind_image_reader(py::module_& m) {
  m.def(
      "read_image",
      [](const std::filesystem::path& path) {
        const ColorImage im = [&] {
          py::gil_scoped_release free;
          return io::read_color(path);
        }();
        py::array_t<std::uint8_t> out({im.height, im.width, 3});
        std::memcpy(out.mutable_data(), static_cast<const void*>(im.data.data()), std::size_t(out.size()));
        return out;
      },
      py::arg("path"),
      "An 8-bit image file (PNG, JPEG) as an H×W×3 uint8 RGB array (grey images become RGB); cropsight.Error "
      "naming the file for a missing or unreadable one.");
}

}  // namespace

void bind_core(py::module_& m) {
  bind_camera(m);
  bind_frame(m);
  bind_sequence(m);
  bind_image_reader(m);
}

}  // namespace cropsight::python
