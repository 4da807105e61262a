// Reading the scene's `constraints:` list: distance constraints between a particle and a particle,
// a fixed point or a point carried by a collider (drapelab/distance_constraints.hpp).
#pragma once

#include <yaml-cpp/yaml.h>

#include <vector>

#include "drapelab/cloth_model.hpp"
#include "drapelab/distance_constraints.hpp"
#include "drapelab/scene/scene.hpp"
#include "yaml_reader.hpp"

namespace drapelab::scene {

// Reads and checks every constraint against the scene's cloth and colliders; problems go to
// `reader`. `model` is the scene's cloth (its rest pose gives the default lengths); null when the
// cloth could not be built, and then the ends are checked for form only.
// A particle of the scene's cloth given as {index: k} or [i, j] (a grid's column and row); its
// index, checked on the cloth when `model` is built (0 when it is not). Problems go to `reader`.
std::optional<int> read_cloth_particle(SceneReader& reader, const YAML::Node& node,
                                       const std::string& path, const Scene& scene,
                                       const ClothModel* model);

std::vector<DistanceConstraint> read_constraints(SceneReader& reader, const YAML::Node& list,
                                                 const Scene& scene, const ClothModel* model);

}  // namespace drapelab::scene
