// Builds the solver a scene's solver entry names.
#pragma once

#include <memory>

#include "drapelab/cloth_model.hpp"
#include "drapelab/cloth_state.hpp"
#include "drapelab/scene/scene.hpp"
#include "drapelab/solver.hpp"
#include "drapelab/world.hpp"

namespace drapelab::runner {

// `world` is what every solver of the scene simulates (build_world, scene_setup.hpp); the spec
// adds this solver's numerics, and `model` is the scene's cloth (our solver with model: continuum
// runs the continuum's elements of it).
std::unique_ptr<Solver> make_solver(const scene::Scene& scene, const scene::SolverSpec& spec,
                                    std::shared_ptr<const ClothModel> model,
                                    const ClothState& initial, const World& world);

}  // namespace drapelab::runner
