// The drapelab Python module: load a scene (a file or a dict), step its solvers frame by frame and
// read their state and metrics as NumPy arrays, run a whole scene into a run folder, and read a
// run or sweep folder's tables. docs/python.md describes it.
#include <pybind11/pybind11.h>

#include "bindings.hpp"

PYBIND11_MODULE(drapelab, module) {
  module.doc() =
      "drapelab: a cloth laboratory comparing a spring-damper cloth with Bullet's cloths.\n"
      "  sim = drapelab.load('scenes/curtain.yaml', overrides={'duration': 1})\n"
      "  sim.step(frames=30)\n"
      "  sim.metrics('ours')['max_stretch']";
  module.attr("__version__") = DRAPELAB_VERSION;
  drapelab::python::bind_errors(module);
  drapelab::python::bind_simulation(module);
  drapelab::python::bind_run_folders(module);
}
