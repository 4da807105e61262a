// Warnings about a valid scene that may still go wrong: a solver's dt above its integrator's stable
// step estimate, or no stable step at all; self-collision asked of a solver without it. validate
// and run print the same ones.
#pragma once

#include <string>
#include <vector>

#include "drapelab/cloth_model.hpp"
#include "drapelab/scene/scene.hpp"

namespace drapelab::cli {

// One line per warning, without the "warning: " prefix.
std::vector<std::string> scene_warnings(const scene::Scene& scene, const ClothModel& model);

}  // namespace drapelab::cli
