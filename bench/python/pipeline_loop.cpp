// _cropsight_bench: the C++ side of bench/python/bench_python_overhead.py. It builds the broccoli
// pipeline with the same make_pipeline spec as the Python package, reads the same sequence, and
// runs it over the frames in one C++ loop, so that the benchmark times the same work with and
// without a Python call per frame, in one process. It holds its own objects: pybind11 types are
// not passed between the two extension modules (each links its own copy of the library).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "cropsight/io/sequence.hpp"
#include "cropsight/pipeline/broccoli/make_pipeline.hpp"

namespace py = pybind11;

namespace {
struct BroccoliLoop {
  std::unique_ptr<cropsight::pipeline::broccoli::Pipeline> pipe;
  std::vector<cropsight::RgbdFrame> frames;

  BroccoliLoop(const std::string& sequence, const std::string& model, const std::vector<std::string>& sets)
      : pipe(cropsight::pipeline::broccoli::make_pipeline({"", sets, model})) {
    const cropsight::io::SequenceReader reader(sequence);
    for (int i = 0; i < reader.size(); ++i) frames.push_back(reader.read(i));
  }
  // Seconds for one pass over the frames, and the detections found.
  py::tuple run() {
    std::size_t found = 0;
    double seconds = 0;
    {
      py::gil_scoped_release free;
      const auto start = std::chrono::steady_clock::now();
      for (const auto& f : frames) found += pipe->process(f).detections.size();
      seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    return py::make_tuple(seconds, found);
  }
  // Seconds for `n` calls on a 4×4 frame without a depth return (the sequence's focal lengths):
  // the pipeline has almost nothing to do, so what the Python loop adds to this is the call's own cost.
  double run_empty(int n) {
    cropsight::RgbdFrame empty;
    empty.camera = frames.at(0).camera;
    empty.camera.width = empty.camera.height = 4;
    empty.camera.cx = empty.camera.cy = 1.5;
    empty.depth = cropsight::DepthImage(4, 4, 0);
    py::gil_scoped_release free;
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < n; ++i) pipe->process(empty);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
};
}  // namespace

PYBIND11_MODULE(_cropsight_bench, m) {
  py::class_<BroccoliLoop>(m, "BroccoliLoop")
      .def(py::init<std::string, std::string, std::vector<std::string>>())
      .def("run", &BroccoliLoop::run, "Seconds to run every frame in one C++ loop, and the detections found.")
      .def("run_empty", &BroccoliLoop::run_empty, "Seconds for n calls on a frame without depth.");
}
