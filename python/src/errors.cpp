// cropsight.Error: the library's one error type (core/error.hpp) as a Python exception, with the
// same one line as its message and the two parts as attributes (where: a file, a key, an
// argument; problem: what is wrong).
#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "cropsight/core/error.hpp"

namespace cropsight::python {

void bind_errors(py::module_& m) {
  // A module attribute (not a static object) owns the class: no global state in the extension.
  py::object error_type = py::reinterpret_steal<py::object>(PyErr_NewExceptionWithDoc(
      "cropsight.Error",
      "An error of the cropsight library: str(e) is one line 'WHERE: PROBLEM'; e.where names the file, key or "
      "argument, e.problem says what is wrong.",
      PyExc_RuntimeError, nullptr));
  if (!error_type) throw py::error_already_set();
  // Class-level defaults, so that an Error raised from Python code (no parts) has them too.
  error_type.attr("where") = py::str("");
  error_type.attr("problem") = py::str("");
  m.attr("Error") = error_type;
  // A translator is a plain function: it finds the class through the module that owns it.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      py::object type = py::module_::import("cropsight._cropsight").attr("Error");
      py::object instance = type(py::str(e.what()));
      instance.attr("where") = py::str(e.where());
      instance.attr("problem") = py::str(e.problem());
      PyErr_SetObject(type.ptr(), instance.ptr());
    }
  });
}

}  // namespace cropsight::python
