// cropsight.seedling: the broccoli-seedling pipeline (pipeline/seedling/) of make_pipeline on a
// stereo pair, rectified with its calibration by the library (stereo/rectification.hpp).
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cstring>

#include "arrays.hpp"
#include "bindings.hpp"
#include "config.hpp"
#include "cropsight/pipeline/seedling/eval.hpp"
#include "cropsight/pipeline/seedling/make_pipeline.hpp"
#include "cropsight/pipeline/seedling/truth.hpp"
#include "cropsight/stereo/calibration.hpp"
#include "cropsight/stereo/rectification.hpp"
#include "cropsight/stereo/stereo_io.hpp"

namespace cropsight::python {

namespace {

namespace seedling = pipeline::seedling;

void bind_seedling_result(py::module_& m) {
  py::class_<seedling::FrameResult>(
      m, "FrameResult",
      "One pair's result, rectified left camera frame (m): found; points (N×3 float32, the dense seedling "
      "points); pixels (their left-image indices); image_mask (H×W uint8, 255 = seedling); envelope "
      "(length_m, width_m, height_m, volume_m3); top_view_area_m2; plane_normal, plane_d (the soil: n·x + d = "
      "0); centroid; points_total, points_candidates, points_sampled, points_seedling_sampled; stage_ms.")
      .def_readonly("found", &seedling::FrameResult::found)
      .def_property_readonly(
          "points",
          [](py::object self) {
            const auto& r = self.cast<const seedling::FrameResult&>();
            return view(r.points.empty() ? nullptr : r.points[0].data(), {py::ssize_t(r.points.size()), 3}, self);
          })
      .def_property_readonly("pixels",
                             [](py::object self) {
                               const auto& r = self.cast<const seedling::FrameResult&>();
                               return view(r.pixels.data(), {py::ssize_t(r.pixels.size())}, self);
                             })
      .def_property_readonly(
          "image_mask",
          [](py::object self) { return gray_view(self.cast<const seedling::FrameResult&>().image_mask, self); })
      .def_property_readonly("envelope",
                             [](const seedling::FrameResult& r) {
                               py::dict d;
                               d["length_m"] = r.envelope.length, d["width_m"] = r.envelope.width,
                               d["height_m"] = r.envelope.height;
                               d["volume_m3"] = r.envelope.volume();
                               return d;
                             })
      .def_property_readonly("top_view_area_m2", [](const seedling::FrameResult& r) { return r.top_view.area(); })
      .def_property_readonly("plane_normal",
                             [](const seedling::FrameResult& r) { return vector_array(r.plane_normal); })
      .def_readonly("plane_d", &seedling::FrameResult::plane_d)
      .def_property_readonly("centroid", [](const seedling::FrameResult& r) { return vector_array(r.centroid()); })
      .def_readonly("points_total", &seedling::FrameResult::points_total)
      .def_readonly("points_candidates", &seedling::FrameResult::points_candidates)
      .def_readonly("points_sampled", &seedling::FrameResult::points_sampled)
      .def_readonly("points_seedling_sampled", &seedling::FrameResult::points_seedling_sampled)
      .def_property_readonly("stage_ms", [](const seedling::FrameResult& r) { return stage_ms_dict(r.timer); })
      .def("__repr__", [](const seedling::FrameResult& r) {
        return std::string("seedling.FrameResult(found=") + (r.found ? "True" : "False") + ", " +
               std::to_string(r.points.size()) + " points)";
      });
}

// The figures of `eval seedling --json` (without the cv::ml::EM comparison: --no-opencv), as a dict.
py::dict seedling_figures_dict(const seedling::Figures& e) {
  py::list per;
  for (const auto& r : e.per_pair) {
    py::dict k;
    k["pair"] = r.pair, k["iou"] = r.score.iou, k["sensitivity"] = r.score.sensitivity;
    k["volume_ratio"] = r.score.volume_ratio, k["ms"] = r.ms, k["gmm_iterations"] = r.gmm_iterations;
    per.append(k);
  }
  py::dict d;
  d["pairs"] = e.pairs, d["recognition_rate"] = e.recognition_rate, d["sensitivity"] = e.sensitivity;
  d["volume_ratio"] = e.volume_ratio, d["ms_total"] = e.ms_total, d["ms_sgm"] = e.ms_sgm, d["ms_gmm"] = e.ms_gmm;
  d["per_pair"] = per;
  return d;
}

}  // namespace

void bind_seedling(py::module_& m) {
  static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float));  // points are viewed as N×3
  bind_config_class<seedling::Config>(m, "seedling",
                                      "The seedling pipeline's configuration (pipeline/seedling/config.hpp).");
  bind_seedling_result(m);
  py::class_<seedling::Pipeline>(
      m, "Pipeline",
      "The broccoli-seedling recogniser of make_pipeline: config = a preset name or YAML file (default "
      "seedling), sets = {key: value} (help(cropsight.seedling.Config)).\n\n"
      "Thread-safety: process() keeps no state between pairs: one Pipeline may serve several threads at once "
      "(it releases the GIL).")
      .def(py::init([](const std::string& config, const py::object& sets) {
             pipeline::PipelineSpec spec{config, sets_from(sets)};
             // Built with the GIL held: loading a model is not thread-safe (libsvm's svm_load_model
             // parses with strtok), so Python threads build their pipelines one at a time.
             return seedling::make_pipeline(spec);
           }),
           py::kw_only(), py::arg("config") = "", py::arg("sets") = py::none())
      .def(
          "process",
          [](const seedling::Pipeline& p, const py::object& left, const py::object& right,
             const std::filesystem::path& calibration) {
            ColorImage l = color_from_array(left, "left"), r = color_from_array(right, "right");
            py::gil_scoped_release free;
            const auto calib = stereo::load_calibration(calibration);
            const auto pair = stereo::rectify_pair(calib, std::move(l), std::move(r), "left");
            return p.process(pair.left, pair.right, pair.geometry, "left");
          },
          py::arg("left"), py::arg("right"), py::arg("calibration"),
          "Detects the seedling in a stereo pair: left, right H×W×3 uint8 RGB as the camera took them, "
          "calibration the stereo calibration file (YAML, docs/formats.md); the library rectifies the pair.")
      .def(
          "evaluate",
          [](const seedling::Pipeline& p, const std::filesystem::path& data, const py::object& calib) {
            // None, not a default path: Python's Path('') is '.'.
            const auto calibration = calib.is_none() ? std::filesystem::path() : calib.cast<std::filesystem::path>();
            const auto figures = [&] {
              py::gil_scoped_release free;
              return seedling::evaluate_seedling_dataset(seedling::open_dataset(data, calibration), p, {});
            }();
            return seedling_figures_dict(figures);
          },
          py::arg("data"), py::arg("calibration") = py::none(),
          "The figures of eval seedling --json --no-opencv on a folder written by simulate seedling "
          "(calibration: default DATA/rig.yaml): pairs, recognition_rate, sensitivity, volume_ratio, "
          "ms_total, ms_sgm, ms_gmm, per_pair.")
      .def_property_readonly("config", [](const seedling::Pipeline& p) { return config_values(p.config()); });
  m.def(
      "read_pair",
      [](const std::filesystem::path& left, const std::filesystem::path& right) {
        auto pair = [&] {
          py::gil_scoped_release free;
          return stereo::read_color_pair(left, right);
        }();
        py::array_t<std::uint8_t> l({pair.first.height, pair.first.width, 3}),
            r({pair.second.height, pair.second.width, 3});
        std::memcpy(l.mutable_data(), static_cast<const void*>(pair.first.data.data()), std::size_t(l.size()));
        std::memcpy(r.mutable_data(), static_cast<const void*>(pair.second.data.data()), std::size_t(r.size()));
        return py::make_tuple(l, r);
      },
      py::arg("left"), py::arg("right"),
      "Reads a stereo pair's image files as two H×W×3 uint8 RGB arrays (grey images become RGB); "
      "cropsight.Error naming the file for a missing, unreadable or mismatched one.");
}

}  // namespace cropsight::python
