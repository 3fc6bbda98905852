// cropsight.grape: the grape pipeline (pipeline/grape/) of make_pipeline: the point segmenter on
// a cloud of N×9 points, and the cloud reader of the dataset's text format.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "config.hpp"
#include "cropsight/io/grape_text.hpp"
#include "cropsight/pipeline/grape/cloud_files.hpp"
#include "cropsight/pipeline/grape/eval.hpp"
#include "cropsight/pipeline/grape/make_pipeline.hpp"
#include "cropsight/pipeline/grape/truth.hpp"
#include "frames.hpp"

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

// boxes: (category, x, y, width, height[, score]) each; category 1 = bunch, 2 = peduncle.
std::vector<grape::Detection> boxes_from(const py::object& boxes) {
  std::vector<grape::Detection> out;
  long k = 0;
  for (const py::handle& item : boxes) {
    const auto t = py::reinterpret_borrow<py::sequence>(item);
    if (!py::isinstance<py::sequence>(item) || (t.size() != 5 && t.size() != 6))
      throw py::value_error("boxes[" + std::to_string(k) +
                            "]: expected (category, x, y, width, height[, score]), got " + std::string(py::repr(item)));
    grape::Detection d;
    d.category = t[0].cast<int>();
    d.box = {t[1].cast<int>(), t[2].cast<int>(), t[3].cast<int>(), t[4].cast<int>()};
    if (t.size() == 6) d.score = t[5].cast<float>();
    d.annotation = k++;
    out.push_back(d);
  }
  return out;
}

py::dict bunch_dict(const grape::Bunch& b) {
  py::dict d;
  d["roi"] = py::make_tuple(b.roi.x, b.roi.y, b.roi.width, b.roi.height);
  d["points"] = array_from(b.cloud);
  d["labels"] = py::array_t<int>(py::ssize_t(b.cloud.labels.size()), b.cloud.labels.data());
  d["label_counts"] = grape::label_counts(b.cloud);
  if (b.cut_point) {
    py::dict c;
    c["position_m"] = vector_array(b.cut_point->position);
    c["direction"] = vector_array(b.cut_point->direction);
    c["confidence"] = b.cut_point->confidence;
    d["cut_point"] = c;
  } else {
    d["cut_point"] = py::none();
  }
  return d;
}

py::dict result_dict(const grape::FrameResult& r) {
  py::dict d;
  py::list bunches;
  for (const auto& b : r.bunches) bunches.append(bunch_dict(b));
  d["bunches"] = bunches;
  d["detections"] = r.detections.size();
  d["outside_image"] = r.outside.size();
  d["stage_ms"] = stage_ms_dict(r.timer);
  return d;
}

// The figures of `eval grape --json` (Table 2 of Luo et al. and the protocols), as a dict.
py::dict figures_dict(const grape::Figures& e) {
  const auto& m = e.confusion;
  py::dict d;
  d["clouds"] = e.clouds, d["points"] = e.points;
  d["oacc"] = m.overall_accuracy(), d["macc"] = m.mean_accuracy(), d["miou"] = m.mean_iou();
  py::list per_class;
  for (int c = 0; c < m.num_classes(); ++c) {
    py::dict k;
    k["label"] = c, k["points"] = m.truth_count(c), k["accuracy"] = m.class_accuracy(c), k["iou"] = m.class_iou(c);
    per_class.append(k);
  }
  d["per_class"] = per_class;
  d["ms_per_cloud"] = e.ms_per_cloud();
  py::dict protocols;
  for (const auto& p : grape::grape_protocols(e)) {
    py::dict k;
    k["classes"] = p.classes, k["miou"] = p.miou;
    protocols[py::str(p.name)] = k;
  }
  d["protocols"] = protocols;
  return d;
}

void bind_grape_pipeline(py::module_& m) {
  py::class_<grape::Pipeline>(
      m, "Pipeline",
      "The grape pipeline of make_pipeline: model = the segmenter (a shipped model's name, a preset such as "
      "grape-best, or a file; default grape-best), config = the pipeline preset (default grape-camera), sets = "
      "{key: value} (segmenter.* keys set the segmenter), threads = the segmenter's worker threads (0 = the "
      "preset's).\n\nThread-safety: segment() is const and may run from several threads at once; it releases "
      "the GIL (the segmenter's own threads run meanwhile).")
      .def(py::init([](const std::string& model, const std::string& config, const py::object& sets, int threads,
                       const std::string& detector) {
             pipeline::PipelineSpec spec{config, sets_from(sets), model, detector, threads};
             // Built with the GIL held: loading a model is not thread-safe (libsvm's svm_load_model
             // parses with strtok), so Python threads build their pipelines one at a time.
             return grape::make_pipeline(spec);
           }),
           py::kw_only(), py::arg("model") = "", py::arg("config") = "", py::arg("sets") = py::none(),
           py::arg("threads") = 0, py::arg("detector") = "")
      .def(
          "process",
          [](grape::Pipeline& p, const py::object& frame, const py::object& boxes) {
            if (!py::isinstance<RgbdFrame>(frame)) throw py::type_error("frame: expected a cropsight.Frame");
            const RgbdFrame& f = frame.cast<const RgbdFrame&>();
            grape::FrameResult r;
            if (boxes.is_none()) {
              py::gil_scoped_release free;
              r = p.process(f);
            } else {
              const auto given = boxes_from(boxes);
              py::gil_scoped_release free;
              r = p.process(f, given);
            }
            return result_dict(r);
          },
          py::arg("frame"), py::arg("boxes") = py::none(),
          "Every step on one frame (colour registered to depth): boxes = [(category, x, y, width, height[, "
          "score]), ...] (category 1 = bunch, 2 = peduncle; pixels) or None for the pipeline's detector "
          "(detector=...). Returns a dict: bunches (each: roi, points N×9 in metres, camera frame, labels, "
          "label_counts, cut_point None or {position_m, direction, confidence}), detections, outside_image, "
          "stage_ms. Not thread-safe with a detector; without one process() is const.")
      .def(
          "segment",
          [](const grape::Pipeline& p, const py::object& points) {
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
      .def(
          "evaluate",
          [](const grape::Pipeline& p, const std::filesystem::path& folder, int limit) {
            if (limit < 0)
              throw py::value_error("limit: must be at least 1 (0 = every cloud), got " + std::to_string(limit));
            py::gil_scoped_release free;
            auto files = grape::list_cloud_files(folder.string());
            if (limit > 0 && std::size_t(limit) < files.size()) files.resize(std::size_t(limit));
            const auto figures = grape::evaluate_grape(p.segmenter().model(), grape::load_grape_clouds(files));
            py::gil_scoped_acquire gil;
            return figures_dict(figures);
          },
          py::arg("clouds"), py::kw_only(), py::arg("limit") = 0,
          "The segmenter's figures on a folder of labelled clouds (the first `limit`, 0 = all, in the order of "
          "eval grape --limit): the dict eval grape --json prints (oacc, macc, miou, per_class, protocols, "
          "ms_per_cloud, clouds, points).")
      .def_property_readonly("segmenter_mode",
                             [](const grape::Pipeline& p) { return std::string(p.segmenter().mode()); })
      .def_property_readonly("config", [](const grape::Pipeline& p) { return config_values(p.config()); });
}

}  // namespace

void bind_grape(py::module_& m) {
  bind_config_class<grape::Config>(m, "grape", "The grape pipeline's configuration (pipeline/grape/config.hpp).");
  bind_grape_pipeline(m);
  m.def(
      "read_cloud",
      [](const std::filesystem::path& path) {
        const Cloud c = [&] {
          py::gil_scoped_release free;
          return io::read_grape_text(path);
        }();
        return py::make_tuple(array_from(c), py::array_t<int>(py::ssize_t(c.labels.size()), c.labels.data()));
      },
      py::arg("path"),
      "Reads a cloud of the grape dataset's text format: (points N×9 float32: x y z nx ny nz r g b, labels N int32). "
      "cropsight.Error naming the file and line for a malformed one.");
}

}  // namespace cropsight::python
