// cropsight.Box and cropsight.Detector: the project's 2D detector (CenterNet with masks; .pt through
// the libtorch plugin or .onnx through OpenCV DNN, nn/center_onnx.hpp) on an image array.
#include <pybind11/stl.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "cropsight/core/detection2d.hpp"
#include "cropsight/nn/center_backend.hpp"

namespace cropsight::python {

namespace {
py::tuple box_corners(const Detection2D& d) { return py::make_tuple(d.x1, d.y1, d.x2, d.y2); }
}  // namespace

void bind_detector(py::module_& m) {
  py::class_<Detection2D>(m, "Box",
                          "A 2D detection: corners (x1, y1, x2, y2) in pixels (the box covers [x1, x2) × [y1, "
                          "y2)), class_id (an index into the detector's class_names), score in [0, 1].")
      .def_property_readonly("corners", &box_corners)
      .def_readonly("class_id", &Detection2D::class_id)
      .def_readonly("score", &Detection2D::score)
      .def("__repr__", [](const Detection2D& d) {
        return "Box(corners=" + std::string(py::repr(box_corners(d))) + ", class_id=" + std::to_string(d.class_id) +
               ", score=" + std::string(py::repr(py::float_(d.score))) + ")";
      });
  py::class_<Detector2D>(m, "Detector",
                         "The project's 2D detector (docs/pipelines/detector.md): model = a shipped model's name "
                         "(detector-grape: libtorch where its plugin is installed, else OpenCV DNN) or a file, .pt "
                         "(libtorch plugin) or .onnx (OpenCV DNN); threads = libtorch threads. detect(image) returns "
                         "the boxes, best first.\n\nThread-safety: not "
                         "thread-safe (it reuses buffers); one Detector per thread. detect() releases the GIL.")
      .def(py::init([](const std::string& model, int threads) {
             // Built with the GIL held, as the pipelines (model loading is not thread-safe).
             return nn::open_center_detector(model, nn::DetectorRuntime::automatic, threads);
           }),
           py::kw_only(), py::arg("model"), py::arg("threads") = 1)
      .def(
          "detect",
          [](Detector2D& d, const py::object& image) {
            const ColorImage im = color_from_array(image, "image");
            py::gil_scoped_release free;
            return d.detect({&im, nullptr});
          },
          py::arg("image"), "Boxes in an H×W×3 uint8 RGB image, best score first.")
      .def_property_readonly("class_names", &Detector2D::class_names);
}

}  // namespace cropsight::python
