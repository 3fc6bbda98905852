// cropsight.Detection (core/detection.hpp): one found crop instance, as the broccoli and grape
// pipelines return it.
#include <pybind11/stl.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "cropsight/core/detection.hpp"

namespace cropsight::python {

void bind_detection(py::module_& m) {
  py::class_<Detection>(m, "Detection",
                        "One found instance. score: classifier score (higher = more confident); centroid: "
                        "metres, camera frame; box: (x, y, width, height) pixels; pixels: indices into the "
                        "frame's H×W image (row * W + column); diameter_m: size estimate in metres or None when "
                        "not measured; track_id: the field map's head id or -1. A plain value.")
      .def_readonly("score", &Detection::score)
      .def_readonly("label", &Detection::label, "class id (1 = the target crop)")
      .def_property_readonly("centroid", [](const Detection& d) { return vector_array(d.centroid); })
      .def_property_readonly(
          "box", [](const Detection& d) { return py::make_tuple(d.box.x, d.box.y, d.box.width, d.box.height); })
      .def_property_readonly("pixels",
                             [](py::object self) {
                               const auto& d = self.cast<const Detection&>();
                               return view(d.indices.data(), {py::ssize_t(d.indices.size())}, self);
                             })
      .def_property_readonly("diameter_m",
                             [](const Detection& d) -> py::object {
                               return d.size_m > 0 ? py::object(py::float_(d.size_m)) : py::object(py::none());
                             })
      .def_readonly("track_id", &Detection::track_id)
      .def(
          "mask",
          [](const Detection& d, int width, int height) {
            py::array_t<bool> out({height, width});
            auto* p = out.mutable_data();
            std::fill(p, p + out.size(), false);
            for (int i : d.indices) {
              if (i < 0 || i >= width * height)
                throw py::value_error("mask: a pixel index lies outside the " + std::to_string(width) + "x" +
                                      std::to_string(height) + " image");
              p[i] = true;
            }
            return out;
          },
          py::arg("width"), py::arg("height"), "H×W bool mask of the detection's pixels (the frame's size).")
      .def("__repr__", [](const Detection& d) {
        return "Detection(score=" + std::string(py::repr(py::float_(d.score))) + ", centroid=(" +
               std::string(py::repr(py::float_(d.centroid.x()))) + ", " +
               std::string(py::repr(py::float_(d.centroid.y()))) + ", " +
               std::string(py::repr(py::float_(d.centroid.z()))) + "), pixels=" + std::to_string(d.indices.size()) +
               (d.track_id >= 0 ? ", track_id=" + std::to_string(d.track_id) : std::string()) + ")";
      });
}

}  // namespace cropsight::python
