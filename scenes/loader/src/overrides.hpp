// --set key.path=value: edits the parsed YAML tree before validation, so an override is checked
// exactly like the file (and its errors name the override instead of a line).
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "yaml_reader.hpp"

namespace drapelab::scene {

// Applies each override in order. Reports malformed overrides through `reader` and records every
// overridden path as the origin of its errors. Returns false when an override could not be applied.
bool apply_overrides(YAML::Node& root, const std::vector<std::string>& overrides,
                     SceneReader& reader);

}  // namespace drapelab::scene
