// The extension module cropsight._cropsight; the package python/cropsight/ re-exports it.
#include "bindings.hpp"

PYBIND11_MODULE(_cropsight, m) {
  using namespace cropsight::python;
  m.doc() = "cropsight's C++ library (the package cropsight re-exports it; docs/python.md)";
  bind_errors(m);
  bind_core(m);
  bind_detection(m);
  bind_detector(m);
  bind_bags(m);
  auto broccoli = m.def_submodule("broccoli", "Broccoli heads from depth frames (Montes 2020, Kusumam 2017)");
  bind_broccoli(broccoli);
  auto potato = m.def_submodule("potato", "Potatoes on an aeroponic rig: the harvest target per RGB-D frame");
  bind_potato(potato);
  auto seedling = m.def_submodule("seedling", "Broccoli seedlings from rectified stereo pairs");
  bind_seedling(seedling);
  auto grape = m.def_submodule("grape", "Grape bunches: ROI clouds, point segmentation, cut points");
  bind_grape(grape);
  auto simulate = m.def_submodule("simulate", "The simulators that make the examples' and tests' data");
  bind_simulate(simulate);
}
