// Reading the scene's `colliders:` list (shared by every solver).
#pragma once

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <string>
#include <vector>

#include "drapelab/collider.hpp"
#include "drapelab/scene/scene.hpp"
#include "yaml_reader.hpp"

namespace drapelab::scene {

// Reads and checks every collider; problems go to `reader`. Friction defaults come from `contact`.
// A mesh collider's file is read relative to `folder` (the scene file's); what is odd about its
// mesh but still usable goes to `warnings`, each with its file and line.
std::vector<Collider> read_colliders(SceneReader& reader, const YAML::Node& list,
                                     const ContactSpec& contact,
                                     const std::filesystem::path& folder,
                                     std::vector<std::string>& warnings);

}  // namespace drapelab::scene
