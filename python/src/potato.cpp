// cropsight.potato: the potato pipeline (pipeline/potato/) built with make_pipeline; a frame in,
// the harvest target message (HarvestTarget) and the boxes that led to it out.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "config.hpp"
#include "cropsight/pipeline/potato/eval.hpp"
#include "cropsight/pipeline/potato/make_pipeline.hpp"
#include "frames.hpp"

namespace cropsight::python {

namespace {

namespace potato = pipeline::potato;

py::tuple target_corners(const Detection2D& d) { return py::make_tuple(d.x1, d.y1, d.x2, d.y2); }  // as cropsight.Box

void bind_potato_values(py::module_& m) {
  py::class_<potato::HarvestTarget>(
      m, "HarvestTarget",
      "The harvest message of one frame (paper Table 3.2): detection, depth_ok, x, y, z (m, camera frame), "
      "height, width (m), angle (rad, counter-clockwise from the image x axis), angle_ok, cut, target_id (0 = "
      "none), state (selecting | detected | tracked | lost), score, box (pixels) and frame, timestamp (s). A "
      "plain value.")
      .def_readonly("frame", &potato::HarvestTarget::frame)
      .def_readonly("timestamp", &potato::HarvestTarget::timestamp)
      .def_readonly("detection", &potato::HarvestTarget::detection)
      .def_readonly("depth_ok", &potato::HarvestTarget::depth_ok)
      .def_readonly("x", &potato::HarvestTarget::x)
      .def_readonly("y", &potato::HarvestTarget::y)
      .def_readonly("z", &potato::HarvestTarget::z)
      .def_readonly("height", &potato::HarvestTarget::height)
      .def_readonly("width", &potato::HarvestTarget::width)
      .def_readonly("angle", &potato::HarvestTarget::angle)
      .def_readonly("angle_ok", &potato::HarvestTarget::angle_ok)
      .def_readonly("cut", &potato::HarvestTarget::cut)
      .def_readonly("target_id", &potato::HarvestTarget::target_id)
      .def_property_readonly("state", [](const potato::HarvestTarget& t) { return config_name(t.state); })
      .def_readonly("score", &potato::HarvestTarget::score)
      .def_property_readonly("box",
                             [](const potato::HarvestTarget& t) -> py::object {
                               return t.detection ? py::object(target_corners(t.box)) : py::object(py::none());
                             })
      .def("__repr__", [](const potato::HarvestTarget& t) {
        return "HarvestTarget(frame=" + std::to_string(t.frame) + ", detection=" + (t.detection ? "True" : "False") +
               ", state=" + config_name(t.state) + ", xyz=(" + std::string(py::repr(py::float_(t.x))) + ", " +
               std::string(py::repr(py::float_(t.y))) + ", " + std::string(py::repr(py::float_(t.z))) + "))";
      });
  py::class_<potato::FrameResult>(
      m, "FrameResult",
      "One frame's result: target (the HarvestTarget), detections (Box list), "
      "positions (per box: (x, y, z) m, camera frame), ripe (per box), stage_ms. Boxes are cropsight.Box.")
      .def_readonly("target", &potato::FrameResult::target)
      .def_readonly("detections", &potato::FrameResult::detections)
      .def_property_readonly("positions",
                             [](const potato::FrameResult& r) {
                               py::list out;
                               for (const auto& p : r.positions) out.append(vector_array(p.xyz));
                               return out;
                             })
      .def_property_readonly(
          "ripe", [](const potato::FrameResult& r) { return std::vector<bool>(r.ripe.begin(), r.ripe.end()); })
      .def_property_readonly("stage_ms", [](const potato::FrameResult& r) { return stage_ms_dict(r.timer); });
}

py::dict axis_dict(const potato::AxisError& a) {
  py::dict d;
  d["mean_mm"] = a.mean_mm, d["mae_mm"] = a.mae_mm, d["std_mm"] = a.std_mm;
  return d;
}

// The figures of `eval potato --json` (without --frames), as a dict.
py::dict potato_figures_dict(const potato::SequenceEvaluation& r) {
  const potato::Figures& e = r.figures;
  const potato::StageTimes& t = r.ms;
  py::dict d, position, cut, ms;
  d["frames"] = e.frames, d["frames_with_target"] = e.frames_with_target, d["frames_matched"] = e.frames_matched;
  d["frames_on_target"] = e.frames_on_target, d["frames_positioned"] = e.frames_positioned;
  d["frames_cut"] = e.frames_cut, d["targets"] = e.targets, d["target_switches"] = e.target_switches;
  d["lost_events"] = e.lost_events;
  position["x"] = axis_dict(e.x), position["y"] = axis_dict(e.y), position["z"] = axis_dict(e.z);
  cut["x"] = axis_dict(e.cut_x), cut["y"] = axis_dict(e.cut_y), cut["z"] = axis_dict(e.cut_z);
  d["position"] = position, d["position_cut"] = cut;
  d["length_mae_mm"] = e.length_mae_mm, d["width_mae_mm"] = e.width_mae_mm, d["angle_mae_deg"] = e.angle_mae_deg;
  d["angles"] = e.angles, d["angle_mae_full_view_deg"] = e.angle_mae_full_view_deg;
  d["angles_full_view"] = e.angles_full_view;
  ms["detect"] = t.detect, ms["locate"] = t.locate, ms["track"] = t.track, ms["orient"] = t.orient;
  ms["total"] = t.total, ms["max"] = t.max_total;
  d["ms_per_frame"] = ms;
  return d;
}

}  // namespace

void bind_potato(py::module_& m) {
  bind_config_class<potato::Config>(m, "potato", "The potato pipeline's configuration (pipeline/potato/config.hpp).");
  bind_potato_values(m);
  py::class_<potato::Pipeline>(
      m, "Pipeline",
      "The potato pipeline of make_pipeline: config = a preset name or YAML file (default potato), sets = "
      "{key: value} (help(cropsight.potato.Config)), model = a detector model where the preset runs one.\n\n"
      "Thread-safety: not thread-safe (it tracks its target across frames); one Pipeline per thread. "
      "process() releases the GIL.")
      .def(py::init([](const std::string& config, const py::object& sets, const std::string& model) {
             pipeline::PipelineSpec spec{config, sets_from(sets), model};
             // Built with the GIL held: loading a model is not thread-safe (libsvm's svm_load_model
             // parses with strtok), so Python threads build their pipelines one at a time.
             return potato::make_pipeline(spec);
           }),
           py::kw_only(), py::arg("config") = "", py::arg("sets") = py::none(), py::arg("model") = "")
      .def(
          "process",
          [](potato::Pipeline& p, const py::object& frame, const py::object& depth, const py::object& color,
             const py::object& camera) {
            RgbdFrame storage;
            const RgbdFrame& f = frame_argument(frame, depth, color, camera, storage);
            if (f.color.empty()) throw py::value_error("color: the potato pipeline needs a colour image");
            py::gil_scoped_release free;
            return p.process(f);
          },
          py::arg("frame") = py::none(), py::kw_only(), py::arg("depth") = py::none(), py::arg("color") = py::none(),
          py::arg("camera") = py::none(),
          "One frame: process(frame) or process(color=H×W×3 uint8, depth=H×W uint16 or None, camera=...). "
          "Returns the FrameResult; .target is the harvest message.")
      .def("reset", &potato::Pipeline::reset, "Starts a new approach: drops the target.")
      .def(
          "evaluate",
          [](potato::Pipeline& p, const std::filesystem::path& sequence, double min_iou) {
            const auto r = [&] {
              py::gil_scoped_release free;
              return potato::evaluate_potato_sequence(p, sequence, min_iou);
            }();
            return potato_figures_dict(r);
          },
          py::arg("sequence"), py::kw_only(), py::arg("min_iou") = 0.3,
          "The figures of eval potato --json on a sequence written by simulate potato (runs this pipeline "
          "over it from a reset): frames, targets, position errors (mm), angle errors (deg), ms_per_frame.")
      .def_property_readonly("config", [](const potato::Pipeline& p) { return config_values(p.config()); });
}

}  // namespace cropsight::python
