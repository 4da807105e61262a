// Reading the scene's `air:` map: aerodynamic drag, lift and wind (drapelab/air.hpp).
#pragma once

#include <yaml-cpp/yaml.h>

#include <cstdint>

#include "drapelab/air.hpp"
#include "yaml_reader.hpp"

namespace drapelab::scene {

// Reads and checks `air:`; problems go to `reader`. The gusts take the scene's `seed`.
AirSettings read_air(SceneReader& reader, const YAML::Node& node, std::uint64_t seed);

}  // namespace drapelab::scene
