// Reading the scene's `colliders:` list (shared by every solver).
#pragma once

#include <yaml-cpp/yaml.h>

#include <vector>

#include "drapelab/collider.hpp"
#include "drapelab/scene/scene.hpp"
#include "yaml_reader.hpp"

namespace drapelab::scene {

// Reads and checks every collider; problems go to `reader`. Friction defaults come from `contact`.
std::vector<Collider> read_colliders(SceneReader& reader, const YAML::Node& list,
                                     const ContactSpec& contact);

}  // namespace drapelab::scene
