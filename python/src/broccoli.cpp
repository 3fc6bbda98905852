// cropsight.broccoli: the broccoli pipeline (pipeline/broccoli/), its result, field map, config
// and detection evaluator, all built with make_pipeline.
#include <pybind11/stl.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "config.hpp"
#include "cropsight/pipeline/broccoli/eval.hpp"
#include "cropsight/pipeline/broccoli/make_pipeline.hpp"
#include "frames.hpp"

namespace cropsight::python {

namespace {

namespace broccoli = pipeline::broccoli;

// A frame's result with the size of its frame (for label_image()).
struct BroccoliResult {
  broccoli::FrameResult r;
  int width = 0, height = 0;
};

void bind_broccoli_result(py::module_& m) {
  py::class_<tracking::PredictedHead>(
      m, "PredictedHead", "A tracked head this frame missed, where the filter expects it (camera frame, m).")
      .def_readonly("track_id", &tracking::PredictedHead::track_id)
      .def_property_readonly("centroid", [](const tracking::PredictedHead& p) { return vector_array(p.centroid); })
      .def_property_readonly("pixels",
                             [](py::object self) {
                               const auto& p = self.cast<const tracking::PredictedHead&>();
                               return view(p.indices.data(), {py::ssize_t(p.indices.size())}, self);
                             })
      .def("__repr__", [](const tracking::PredictedHead& p) {
        return "PredictedHead(track_id=" + std::to_string(p.track_id) + ")";
      });
  py::class_<BroccoliResult>(m, "FrameResult",
                             "One frame's result: detections (best score first), predicted (tracking: heads this "
                             "frame missed), camera_estimate (tracking: the filter's camera position, field frame, "
                             "m), stage_ms (wall-clock per stage), detect_ms, track_ms. A plain value.")
      .def_property_readonly("frame", [](const BroccoliResult& b) { return b.r.frame; })
      .def_property_readonly("detections", [](const BroccoliResult& b) { return b.r.detections; })
      .def_property_readonly("predicted", [](const BroccoliResult& b) { return b.r.predicted; })
      .def_property_readonly("camera_estimate",
                             [](const BroccoliResult& b) { return vector_array(b.r.association.camera_position); })
      .def_property_readonly("stage_ms", [](const BroccoliResult& b) { return stage_ms_dict(b.r.timer); })
      .def_property_readonly("detect_ms", [](const BroccoliResult& b) { return b.r.detect_ms(); })
      .def_property_readonly("track_ms", [](const BroccoliResult& b) { return b.r.track_ms(); })
      .def(
          "label_image",
          [](const BroccoliResult& b) {
            py::array_t<std::uint16_t> out({b.height, b.width});
            auto* p = out.mutable_data();
            std::fill(p, p + out.size(), std::uint16_t(0));
            for (std::size_t k = 0; k < b.r.detections.size(); ++k)
              for (int i : b.r.detections[k].indices) p[i] = std::uint16_t(k + 1);
            return out;
          },
          "H×W uint16: each pixel's 1-based detection number, 0 = none (what detect broccoli --masks writes).")
      .def("__repr__", [](const BroccoliResult& b) {
        return "broccoli.FrameResult(frame=" + std::to_string(b.r.frame) + ", " +
               std::to_string(b.r.detections.size()) + " detections)";
      });
  py::class_<tracking::TrackedHead>(
      m, "FieldHead",
      "One head of the field map: position (field frame, m, running average), "
      "diameter_mm (corrected, chosen estimator), bbox_mm, hull_mm, harvestable, frames_seen, "
      "partial_frames, first_frame, last_frame, score, mean_detection_score, size_samples.")
      .def_readonly("id", &tracking::TrackedHead::id)
      .def_property_readonly("position", [](const tracking::TrackedHead& h) { return vector_array(h.position); })
      .def_readonly("score", &tracking::TrackedHead::score)
      .def_readonly("frames_seen", &tracking::TrackedHead::frames_seen)
      .def_readonly("partial_frames", &tracking::TrackedHead::partial_frames)
      .def_readonly("first_frame", &tracking::TrackedHead::first_frame)
      .def_readonly("last_frame", &tracking::TrackedHead::last_frame)
      .def_readonly("mean_detection_score", &tracking::TrackedHead::mean_detection_score)
      .def_readonly("size_samples", &tracking::TrackedHead::size_samples)
      .def_readonly("bbox_mm", &tracking::TrackedHead::bbox_mm)
      .def_readonly("hull_mm", &tracking::TrackedHead::hull_mm)
      .def_readonly("diameter_mm", &tracking::TrackedHead::diameter_mm)
      .def_readonly("harvestable", &tracking::TrackedHead::harvestable)
      .def("__repr__", [](const tracking::TrackedHead& h) {
        return "FieldHead(id=" + std::to_string(h.id) +
               ", diameter_mm=" + std::string(py::repr(py::float_(h.diameter_mm))) +
               ", harvestable=" + (h.harvestable ? "True" : "False") + ")";
      });
}

void bind_broccoli_pipeline(py::module_& m) {
  py::class_<broccoli::Pipeline>(
      m, "Pipeline",
      "The broccoli pipeline (detection, sizing, temporal filter, field map) of make_pipeline: model = a shipped "
      "model's name or a file (default broccoli-oes-general), config = a preset name or YAML file over the "
      "config the model records, sets = {key: value} overrides (keys: help(cropsight.broccoli.Config)).\n\n"
      "Thread-safety: not thread-safe; one Pipeline per thread (process() releases the GIL, so pipelines in "
      "several threads run in parallel). Frames of a pass go in increasing order; field_map() ends the pass, "
      "reset() starts the next.")
      .def(py::init([](const std::string& model, const std::string& config, const py::object& sets) {
             pipeline::PipelineSpec spec{config, sets_from(sets), model.empty() ? broccoli::kDefaultModel : model};
             // Built with the GIL held: loading a model is not thread-safe (libsvm's svm_load_model
             // parses with strtok), so Python threads build their pipelines one at a time.
             return broccoli::make_pipeline(spec);
           }),
           py::kw_only(), py::arg("model") = broccoli::kDefaultModel, py::arg("config") = "",
           py::arg("sets") = py::none())
      .def(
          "process",
          [](broccoli::Pipeline& p, const py::object& frame, const py::object& depth, const py::object& color,
             const py::object& camera) {
            RgbdFrame storage;
            const RgbdFrame& f = frame_argument(frame, depth, color, camera, storage);
            BroccoliResult out{{}, f.depth.width, f.depth.height};
            if (f.depth.empty()) throw py::value_error("depth: the broccoli pipeline needs a depth image");
            py::gil_scoped_release free;
            out.r = p.process(f);
            return out;
          },
          py::arg("frame") = py::none(), py::kw_only(), py::arg("depth") = py::none(), py::arg("color") = py::none(),
          py::arg("camera") = py::none(),
          "Runs the pipeline on the next frame of the pass: process(frame) with a cropsight.Frame, or "
          "process(depth=H×W uint16, color=H×W×3 uint8 or None, camera=cropsight.Camera).")
      .def(
          "field_map",
          [](broccoli::Pipeline& p) {
            py::gil_scoped_release free;
            return p.finish();
          },
          "Ends the pass and returns its field map (list of FieldHead; empty without tracking).")
      .def("reset", &broccoli::Pipeline::reset, "Starts a new pass (a fresh temporal filter).")
      .def_property_readonly(
          "config", [](const broccoli::Pipeline& p) { return config_values(p.config()); },
          "The values this pipeline runs with (cropsight.broccoli.Config).");
}

py::dict figures_dict(const broccoli::Figures& r) {
  const auto& c = r.confusion;
  py::dict d;
  d["frames"] = r.frames, d["clusters"] = r.clusters, d["truth_heads"] = r.truth_heads, d["detections"] = r.detections;
  d["tp"] = c.tp, d["fp"] = c.fp, d["tn"] = c.tn, d["fn"] = c.fn;
  d["accuracy"] = c.accuracy(), d["precision"] = c.precision(), d["recall"] = c.recall();
  d["specificity"] = c.specificity(), d["npv"] = c.npv(), d["f1"] = c.f1(), d["kappa"] = c.kappa();
  d["ap50"] = r.ap50, d["map50_95"] = r.map50_95;
  d["truth_heads_in_view"] = r.truth_heads_in_view, d["ap50_in_view"] = r.ap50_in_view;
  d["map50_95_in_view"] = r.map50_95_in_view;
  d["truth_heads_visible"] = r.truth_heads_visible, d["ap50_visible"] = r.ap50_visible;
  d["map50_95_visible"] = r.map50_95_visible;
  d["truth_heads_any_depth"] = r.truth_heads_any_depth, d["ap50_any_depth"] = r.ap50_any_depth;
  d["truth_heads_visible_any_depth"] = r.truth_heads_visible_any_depth;
  d["ap50_visible_any_depth"] = r.ap50_visible_any_depth;
  d["fps"] = r.fps(), d["ms_per_frame"] = r.ms_per_frame();
  return d;
}

// The evaluator keeps a reference to its pipeline: keep_alive ties their lifetimes.
void bind_broccoli_evaluator(py::module_& m) {
  py::class_<broccoli::Evaluator>(
      m, "Evaluator",
      "Table I / II figures of a pipeline's detector over labelled frames (the figures eval broccoli --json "
      "prints). add_frame(frame) runs the pipeline on a frame with labels; figures() returns a dict. Not "
      "thread-safe; uses its pipeline, which must not run elsewhere meanwhile.")
      .def(py::init<broccoli::Pipeline&>(), py::arg("pipeline"), py::keep_alive<1, 2>())
      .def(
          "add_frame",
          [](broccoli::Evaluator& e, const RgbdFrame& frame) {
            py::gil_scoped_release free;
            e.add_frame(frame);
          },
          py::arg("frame"))
      .def("figures", [](const broccoli::Evaluator& e) { return figures_dict(e.figures()); });
}

}  // namespace

void bind_broccoli(py::module_& m) {
  bind_config_class<broccoli::Config>(m, "broccoli",
                                      "The broccoli pipeline's configuration (pipeline/broccoli/config.hpp): detector, "
                                      "detection (truth rules), sizing, tracking, track.");
  bind_broccoli_result(m);
  bind_broccoli_pipeline(m);
  bind_broccoli_evaluator(m);
}

}  // namespace cropsight::python
