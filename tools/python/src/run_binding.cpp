#include "run_binding.hpp"

#include <sstream>

#include "drapelab/runner/run_scene.hpp"
#include "errors.hpp"
#include "interrupt_guard.hpp"

namespace py = pybind11;

namespace drapelab::python {

py::object run_into_folder(const scene::Scene& scene, const std::string& scene_text,
                           const std::vector<std::string>& overrides, const std::string& out,
                           bool force) {
  runner::RunOptions options;
  options.out_dir = out;
  options.force = force;
  options.scene_text = scene_text;
  // summary.json's command: how to make the same run from the command line.
  options.command_line = "drapelab.run (Python): " + scene.name;
  for (const auto& text : overrides) options.command_line += " --set " + text;
  const InterruptGuard guard;
  options.interrupt = guard.flag();
  std::ostringstream log;
  runner::RunResult result;
  {
    const py::gil_scoped_release unlocked;
    result = runner::run_scene(scene, options, log);
  }
  if (result.exit_code == runner::kExitBadInput || result.folder.empty()) {
    std::string message = log.str();
    while (!message.empty() && message.back() == '\n') message.pop_back();
    raise_run_error(message.empty() ? "the run into " + out + " could not start" : message);
  }
  // Progress notes and warnings, as drapelab run prints them.
  if (!log.str().empty()) py::module_::import("sys").attr("stderr").attr("write")(log.str());
  guard.raise_if_interrupted();
  return open_run_folder(result.folder.string());
}

}  // namespace drapelab::python
