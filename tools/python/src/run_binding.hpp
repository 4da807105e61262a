// drapelab.run: a whole scene into a run folder, as `drapelab run` writes it.
#pragma once

#include <pybind11/pybind11.h>

#include <string>
#include <vector>

#include "drapelab/scene/scene.hpp"

namespace drapelab::python {

// Runs `scene` (loaded from `scene_text` with `overrides`) into `out`, the GIL released; Ctrl-C
// stops it after the current step with every file valid, then raises KeyboardInterrupt. Returns
// drapelab.read_run(out). Raises RunError when the folder is refused (one in use, a previous run
// without force) or cannot be written. An unstable solver is no error: its status says so.
pybind11::object run_into_folder(const scene::Scene& scene, const std::string& scene_text,
                                 const std::vector<std::string>& overrides, const std::string& out,
                                 bool force);

// drapelab.read_run(folder).
pybind11::object open_run_folder(const std::string& folder);

}  // namespace drapelab::python
