// Reading the scene's `interactions:` list: scripted drags, as the viewer records them
// (drapelab/drag_track.hpp).
#pragma once

#include <yaml-cpp/yaml.h>

#include <vector>

#include "drapelab/cloth_model.hpp"
#include "drapelab/scene/scene.hpp"
#include "yaml_reader.hpp"

namespace drapelab::scene {

// Reads and checks every drag against the scene's cloth; problems go to `reader`. `model` is the
// scene's cloth, null when it could not be built (then particles are checked for form only).
std::vector<DragSpec> read_interactions(SceneReader& reader, const YAML::Node& list,
                                        const Scene& scene, const ClothModel* model);

}  // namespace drapelab::scene
