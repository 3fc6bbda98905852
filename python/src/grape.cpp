// cropsight.grape: the grape pipeline (pipeline/grape/) of make_pipeline: the point segmenter on
// a cloud of N×9 points, and the cloud reader of the dataset's text format.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "config.hpp"
#include "cropsight/io/grape_text.hpp"
#include "cropsight/pipeline/grape/make_pipeline.hpp"

namespace cropsight::python {

namespace {

namespace grape = pipeline::grape;

// Columns of a point, as the dataset's text files hold them (io/grape_text.hpp).
constexpr int kColumns = 9;

Cloud cloud_from(const py::object& points) {
  int rows = 0;
  const std::vector<float> v = points_from_array(points, "points", kColumns, rows);
  Cloud c;
  c.points.resize(std::size_t(rows)), c.normals.resize(std::size_t(rows)), c.colors.resize(std::size_t(rows));
  for (std::size_t i = 0; i < std::size_t(rows); ++i) {
    const float* p = v.data() + i * kColumns;
    c.points[i] = {p[0], p[1], p[2]};
    c.normals[i] = {p[3], p[4], p[5]};
    c.colors[i] = {p[6], p[7], p[8]};
  }
  c.validate("points");
  return c;
}

py::array_t<float> array_from(const Cloud& c) {
  py::array_t<float> out({py::ssize_t(c.size()), py::ssize_t(kColumns)});
  float* p = out.mutable_data();
  for (std::size_t i = 0; i < c.size(); ++i, p += kColumns) {
    for (int k = 0; k < 3; ++k) p[k] = c.points[i][k];
    for (int k = 0; k < 3; ++k) p[3 + k] = c.has_normals() ? c.normals[i][k] : 0.f;
    for (int k = 0; k < 3; ++k) p[6 + k] = c.has_colors() ? c.colors[i][k] : 0.f;
  }
  return out;
}

}  // namespace

void bind_grape(py::module_& m) {
  bind_config_class<grape::Config>(m, "grape", "The grape pipeline's configuration (pipeline/grape/config.hpp).");
  py::class_<grape::Pipeline>(
      m, "Pipeline",
      "The grape pipeline of make_pipeline: model = the segmenter (a shipped model's name, a preset such as "
      "grape-best, or a file; default grape-best), config = the pipeline preset (default grape-camera), sets = "
      "{key: value} (segmenter.* keys set the segmenter), threads = the segmenter's worker threads (0 = the "
      "preset's).\n\nThread-safety: segment() is const and may run from several threads at once; it releases "
      "the GIL (the segmenter's own threads run meanwhile).")
      .def(py::init([](const std::string& model, const std::string& config, const py::object& sets, int threads) {
             pipeline::PipelineSpec spec{config, sets_from(sets), model};
             spec.threads = threads;
             py::gil_scoped_release free;
             return grape::make_pipeline(spec);
           }),
           py::kw_only(), py::arg("model") = "", py::arg("config") = "", py::arg("sets") = py::none(), py::arg("threads") = 0)
      .def("segment", [](const grape::Pipeline& p, const py::object& points) {
             const Cloud cloud = cloud_from(points);
             std::vector<int> labels;
             {
               py::gil_scoped_release free;
               labels = p.segmenter().segment(cloud);
             }
             return py::array_t<int>(py::ssize_t(labels.size()), labels.data());
           },
           py::arg("points"),
           "Labels every point of a cloud: points N×9 float32/float64, columns x y z nx ny nz r g b (the "
           "dataset's unit-sphere normalised clouds, colours in [0, 1]). Returns N int32 labels.")
      .def_property_readonly("segmenter_mode", [](const grape::Pipeline& p) { return std::string(p.segmenter().mode()); })
      .def_property_readonly("config", [](const grape::Pipeline& p) { return config_values(p.config()); });
  m.def("read_cloud", [](const std::filesystem::path& path) {
    const Cloud c = [&] {
      py::gil_scoped_release free;
      return io::read_grape_text(path);
    }();
    return py::make_tuple(array_from(c), py::array_t<int>(py::ssize_t(c.labels.size()), c.labels.data()));
  }, py::arg("path"),
  "Reads a cloud of the grape dataset's text format: (points N×9 float32: x y z nx ny nz r g b, labels N int32). "
  "cropsight.Error naming the file and line for a malformed one.");
}

}  // namespace cropsight::python
