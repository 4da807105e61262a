// The parts of the Python module, each adding its functions and classes to it.
#pragma once

#include <pybind11/pybind11.h>

namespace drapelab::python {

// drapelab.SceneError (a ValueError): a scene or override refused, every message "file:line: ...".
// drapelab.RunError (a RuntimeError): a run that could not write its folder.
void bind_errors(pybind11::module_& module);
// drapelab.load and drapelab.Simulation.
void bind_simulation(pybind11::module_& module);
// drapelab.run, read_run, read_sweep, read_csv and their folder classes.
void bind_run_folders(pybind11::module_& module);

}  // namespace drapelab::python
