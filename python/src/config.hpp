#pragma once
// A crop's configuration as Python sees it: cropsight.<crop>.Config, a read-only mapping of every
// dotted key to its value text, whose class docstring lists the keys with their documentation,
// unit and range (the config struct's visit(), core/config.hpp), so that help(cs.broccoli.Config)
// is the reference of the keys that sets={...} and presets take.
#include <pybind11/pybind11.h>

#include <string>
#include <tuple>
#include <vector>

#include "cropsight/core/config.hpp"

namespace cropsight::python {

namespace py = pybind11;

/// Key, value text, documentation (with the range), in declaration order.
using ConfigEntries = std::vector<std::tuple<std::string, std::string, std::string>>;

/// One crop's configuration values; `Tag` keeps the crops' classes apart for pybind11.
template <typename Tag>
struct ConfigValues {
  ConfigEntries entries;
};

/// "KEY = DEFAULT\n    DOC" for every key: the docstring body.
std::string config_doc(const std::string& header, const ConfigEntries& defaults);
/// The mapping methods every crop's Config class has.
void add_mapping_methods(py::handle cls, const std::string& crop);

/// cropsight.<crop>.Config for `Cfg` in `m`.
template <typename Cfg>
py::class_<ConfigValues<Cfg>> bind_config_class(py::module_& m, const std::string& crop, const std::string& header) {
  const std::string doc = config_doc(header, dump_config(Cfg{}));
  py::class_<ConfigValues<Cfg>> cls(m, "Config", doc.c_str());
  cls.def(py::init([] { return ConfigValues<Cfg>{dump_config(Cfg{})}; }),
          "The defaults (before any preset or model); pipeline.config holds the values a pipeline runs with.");
  cls.def_readonly("_entries", &ConfigValues<Cfg>::entries);
  add_mapping_methods(cls, crop);
  return cls;
}

/// The values of a running pipeline's config.
template <typename Cfg>
ConfigValues<Cfg> config_values(const Cfg& cfg) {
  return {dump_config(cfg)};
}

/// sets={key: value} (bool → true/false, others str()) or ["key=value", ...] as the spec's sets.
std::vector<std::string> sets_from(const py::object& sets);

}  // namespace cropsight::python
