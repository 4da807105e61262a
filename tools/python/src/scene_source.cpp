#include "scene_source.hpp"

#include "drapelab/run_folder/files.hpp"
#include "errors.hpp"

namespace py = pybind11;

namespace drapelab::python {
namespace {

std::string as_json(const py::handle& value, bool indent) {
  const py::module_ json = py::module_::import("json");
  if (indent) return py::cast<std::string>(json.attr("dumps")(value, py::arg("indent") = 2));
  return py::cast<std::string>(json.attr("dumps")(value));
}

}  // namespace

std::vector<std::string> override_texts(const py::object& overrides) {
  std::vector<std::string> texts;
  if (overrides.is_none()) return texts;
  if (py::isinstance<py::dict>(overrides)) {
    for (const auto& [key, value] : py::cast<py::dict>(overrides)) {
      if (!py::isinstance<py::str>(key))
        throw py::type_error("overrides: every key is a key path such as 'cloth.resolution', got " +
                             py::cast<std::string>(py::repr(key)));
      const std::string text =
          py::isinstance<py::str>(value) ? py::cast<std::string>(value) : as_json(value, false);
      texts.push_back(py::cast<std::string>(key) + "=" + text);
    }
    return texts;
  }
  if (py::isinstance<py::str>(overrides))
    throw py::type_error("overrides: give a dict {'key.path': value} or a list of 'key=value'");
  for (const auto& item : overrides) {
    if (!py::isinstance<py::str>(item))
      throw py::type_error("overrides: a list holds 'key.path=value' strings, got " +
                           py::cast<std::string>(py::repr(item)));
    texts.push_back(py::cast<std::string>(item));
  }
  return texts;
}

LoadedScene load_scene(const py::object& scene, const std::vector<std::string>& texts) {
  LoadedScene loaded;
  if (py::isinstance<py::dict>(scene)) {
    // JSON is YAML: the dict reads exactly as a scene file holding the same keys would.
    loaded.text = as_json(scene, true);
    loaded.result = scene::load_scene_text(loaded.text, "<scene dict>", texts);
  } else {
    const py::object fspath = py::module_::import("os").attr("fspath");
    py::object path;
    try {
      path = fspath(scene);
    } catch (const py::error_already_set&) {
      throw py::type_error("drapelab.load takes a scene file path or a dict, got " +
                           py::cast<std::string>(py::repr(scene)));
    }
    const std::string file = py::cast<std::string>(path);
    loaded.result = scene::load_scene_file(file, texts);
    if (loaded.result.ok()) loaded.text = run_folder::read_file(file);
  }
  if (!loaded.result.ok()) raise_scene_error(loaded.result.errors);
  return loaded;
}

}  // namespace drapelab::python
