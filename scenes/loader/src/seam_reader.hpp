// Reading cloth.seams: pairs of particle lists of the cloth sewn together by stitches.
#pragma once

#include <yaml-cpp/yaml.h>

#include <vector>

#include "drapelab/cloth_model.hpp"
#include "drapelab/scene/scene.hpp"
#include "yaml_reader.hpp"

namespace drapelab::scene {

// Reads and checks every seam against the built cloth `model` (null when it could not be built:
// then only the form is checked). Problems go to `reader`. Stiffness and damping default to the
// cloth's stretch springs'.
std::vector<SeamSpec> read_seams(SceneReader& reader, const YAML::Node& list, const Scene& scene,
                                 const ClothModel* model);

}  // namespace drapelab::scene
