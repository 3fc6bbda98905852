#pragma once
// The pieces of the extension module cropsight._cropsight, one file each (module.cpp wires them).
// The bindings hold no pipeline logic: every result comes from the library's make_pipeline, its
// pipelines and evaluators; this folder only converts between numpy / Python and the library's
// types and releases the GIL while the library works.
#include <pybind11/pybind11.h>

namespace cropsight::python {

namespace py = pybind11;

void bind_errors(py::module_& m);     // cropsight.Error
void bind_core(py::module_& m);       // Camera, Frame, Sequence, read_sequence
void bind_detection(py::module_& m);  // Detection
void bind_detector(py::module_& m);   // Box, Detector
void bind_broccoli(py::module_& m);   // cropsight.broccoli
void bind_potato(py::module_& m);     // cropsight.potato
void bind_seedling(py::module_& m);   // cropsight.seedling
void bind_grape(py::module_& m);      // cropsight.grape
void bind_simulate(py::module_& m);   // cropsight.simulate
void bind_bags(py::module_& m);       // _import_bag (cropsight.read_bag)

}  // namespace cropsight::python
