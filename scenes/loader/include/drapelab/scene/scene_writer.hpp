// Writes a resolved scene as YAML: every key with its value (defaults filled in), units in
// comments. Loading the text again gives the same scene.
#pragma once

#include <string>

#include "drapelab/scene/scene.hpp"

namespace drapelab::scene {

std::string resolved_scene_yaml(const Scene& scene);

}  // namespace drapelab::scene
