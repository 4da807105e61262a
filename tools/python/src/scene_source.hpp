// A scene given from Python: a path (str or os.PathLike) or a dict, with overrides as a dict
// {"key.path": value} or a list of "key.path=value" strings (drapelab run's --set).
#pragma once

#include <pybind11/pybind11.h>

#include <string>
#include <vector>

#include "drapelab/scene/scene_loader.hpp"

namespace drapelab::python {

struct LoadedScene {
  scene::LoadResult result;  // ok: every problem raised SceneError
  std::string text;  // the scene as given (a file's text, or a dict as YAML), for scene.yaml
};

// Loads and validates with `overrides` (override_texts); raises SceneError carrying every loader
// message (file:line: key: ...).
LoadedScene load_scene(const pybind11::object& scene, const std::vector<std::string>& overrides);

// Overrides as "key.path=value" texts. A str value is taken as YAML text, as --set takes it;
// any other value (number, bool, list, dict) is written as JSON, which YAML reads as the same
// value.
std::vector<std::string> override_texts(const pybind11::object& overrides);

}  // namespace drapelab::python
