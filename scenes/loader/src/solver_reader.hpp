// Reading the scene's `solvers:` list: each solver's type, step and type-specific options.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "drapelab/scene/scene.hpp"
#include "yaml_reader.hpp"

namespace drapelab::scene {

// `scene` holds everything read before the solvers (run settings, cloth, colliders, contact), which
// the automatic steps and Bullet's defaults depend on; `model` is its cloth as built, null when the
// cloth is refused.
// Things chosen on the user's behalf (an automatic or rounded dt) are added to `notes`.
std::vector<SolverSpec> read_solvers(SceneReader& reader, const YAML::Node& list,
                                     const Scene& scene, const ClothModel* model,
                                     std::vector<std::string>& notes);

}  // namespace drapelab::scene
