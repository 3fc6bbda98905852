#include "config.hpp"

#include <pybind11/eval.h>
#include <pybind11/stl.h>

#include "bindings.hpp"

namespace cropsight::python {

std::string config_doc(const std::string& header, const ConfigEntries& defaults) {
  std::string doc = header +
                    "\n\nA read-only mapping key -> value text (cfg['key'], cfg.keys(), cfg.items()). The keys, "
                    "with their defaults, are those of presets and of sets={...}:\n\n";
  for (const auto& [key, value, text] : defaults) doc += key + " = " + value + "\n    " + text + "\n";
  return doc;
}

void add_mapping_methods(py::handle cls, const std::string& crop) {
  py::object c = py::reinterpret_borrow<py::object>(cls);
  // Written in Python terms over the entries list: a mapping with a readable repr.
  py::dict ns;
  ns["crop"] = crop;
  py::exec(R"(
def _dict(self):
    return {k: v for k, v, _ in self._entries}
def __getitem__(self, key):
    for k, v, _ in self._entries:
        if k == key:
            return v
    raise KeyError(key)
def keys(self):
    return [k for k, _, _ in self._entries]
def items(self):
    return [(k, v) for k, v, _ in self._entries]
def doc(self, key):
    """The documentation of one key (unit, range, source)."""
    for k, _, d in self._entries:
        if k == key:
            return d
    raise KeyError(key)
def __contains__(self, key):
    return any(k == key for k, _, _ in self._entries)
def __len__(self):
    return len(self._entries)
def __iter__(self):
    return iter(self.keys())
def __repr__(self):
    return 'cropsight.' + crop + '.Config(' + repr(_dict(self)) + ')'
)",
           ns);
  for (const char* name : {"__getitem__", "keys", "items", "doc", "__contains__", "__len__", "__iter__", "__repr__"})
    c.attr(name) = ns[name];
}

std::vector<std::string> sets_from(const py::object& sets) {
  std::vector<std::string> out;
  if (sets.is_none()) return out;
  if (py::isinstance<py::dict>(sets)) {
    for (const auto& [key, value] : sets.cast<py::dict>()) {
      const std::string text =
          py::isinstance<py::bool_>(value) ? (value.cast<bool>() ? "true" : "false") : std::string(py::str(value));
      out.push_back(std::string(py::str(key)) + "=" + text);
    }
    return out;
  }
  if (py::isinstance<py::str>(sets))
    throw py::type_error("sets: expected a dict {key: value} or a list of 'key=value', got a str");
  try {
    return sets.cast<std::vector<std::string>>();
  } catch (const py::cast_error&) {
    throw py::type_error("sets: expected a dict {key: value} or a list of 'key=value', got " +
                         std::string(py::str(sets.get_type().attr("__name__"))) + " object");
  }
}

}  // namespace cropsight::python
