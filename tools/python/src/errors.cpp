#include "errors.hpp"

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.hpp"

namespace py = pybind11;

namespace drapelab::python {
namespace {

// The exception types, created once when the module loads and kept for the interpreter's life.
PyObject* scene_error_type = nullptr;
PyObject* run_error_type = nullptr;

[[noreturn]] void raise(PyObject* type, const py::object& exception) {
  PyErr_SetObject(type, exception.ptr());
  throw py::error_already_set();
}

}  // namespace

void bind_errors(py::module_& module) {
  scene_error_type = PyErr_NewExceptionWithDoc(
      "drapelab.SceneError",
      "A scene or an override was refused. The message holds every problem, one per line, each "
      "naming the file and line (or the override), the key and what was expected; `errors` lists "
      "them.",
      PyExc_ValueError, nullptr);
  run_error_type = PyErr_NewExceptionWithDoc(
      "drapelab.RunError", "A run could not start or write its folder (the message says why).",
      PyExc_RuntimeError, nullptr);
  if (!scene_error_type || !run_error_type) throw py::error_already_set();
  module.add_object("SceneError", py::reinterpret_borrow<py::object>(scene_error_type));
  module.add_object("RunError", py::reinterpret_borrow<py::object>(run_error_type));
}

void raise_scene_error(const std::vector<std::string>& errors) {
  std::string message;
  for (const auto& error : errors) message += (message.empty() ? "" : "\n") + error;
  py::object exception = py::reinterpret_borrow<py::object>(scene_error_type)(message);
  exception.attr("errors") = py::cast(errors);
  raise(scene_error_type, exception);
}

void raise_run_error(const std::string& message) {
  raise(run_error_type, py::reinterpret_borrow<py::object>(run_error_type)(message));
}

}  // namespace drapelab::python
