// cropsight.simulate: the simulators behind `cropsight simulate <crop>`, for examples and tests.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.hpp"
#include "config.hpp"
#include "cropsight/io/config_yaml.hpp"
#include "cropsight/sim/broccoli/broccoli_sim.hpp"

namespace cropsight::python {

void bind_simulate(py::module_& m) {
  m.def(
      "broccoli",
      [](const std::filesystem::path& out, const std::string& variety, int frames, std::uint64_t seed,
         const py::object& sets, bool force) {
        if (frames < 1) throw py::value_error("frames: must be at least 1, got " + std::to_string(frames));
        const std::string preset = "sim-broccoli-" + variety;
        sim::BroccoliSimConfig cfg;
        apply_config(cfg, io::load_preset_with_overrides(preset, sets_from(sets)),
                     "configs/" + preset + ".yaml (with sets)");
        cfg.validate("configs/" + preset + ".yaml (with sets)");
        py::gil_scoped_release free;
        const auto s =
            sim::simulate_broccoli_sequence(cfg, seed, frames, out, io::OutputPolicy{"simulate broccoli", force, {}});
        py::gil_scoped_acquire gil;
        py::dict d;
        d["out"] = out.string(), d["frames"] = s.frames, d["instances"] = s.instances, d["plants"] = s.plants;
        d["harvested"] = s.harvested, d["mean_occlusion"] = s.mean_occlusion, d["valid_fraction"] = s.valid_fraction;
        d["seconds"] = s.seconds;
        return d;
      },
      py::arg("out"), py::kw_only(), py::arg("variety") = "uk", py::arg("frames") = 60, py::arg("seed") = 1,
      py::arg("sets") = py::none(), py::arg("force") = false,
      "Simulates a tractor-mounted ToF camera over a broccoli field and writes the sequence folder `out` (the "
      "same files, byte for byte, as `cropsight simulate broccoli` with the same options). variety: uk, spain, "
      "random, random-wide. force: replace an earlier cropsight output (never anything else). Returns the "
      "summary (frames, instances, plants, harvested, mean_occlusion, valid_fraction, seconds). Thread-safe "
      "for distinct `out` folders.");
}

}  // namespace cropsight::python
