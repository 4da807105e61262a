// Builds the solver a scene's solver entry names.
#pragma once

#include <memory>
#include <vector>

#include "drapelab/cloth_model.hpp"
#include "drapelab/cloth_state.hpp"
#include "drapelab/contact_model.hpp"
#include "drapelab/distance_constraints.hpp"
#include "drapelab/scene/scene.hpp"
#include "drapelab/solver.hpp"

namespace drapelab::runner {

// `contacts` holds the scene's colliders (may be null when there are none). `extra_constraints` are
// added to the scene's (the viewer's live drag).
std::unique_ptr<Solver> make_solver(const scene::Scene& scene, const scene::SolverSpec& spec,
                                    std::shared_ptr<const ClothModel> model,
                                    const ClothState& initial,
                                    std::shared_ptr<const ContactModel> contacts,
                                    const std::vector<DistanceConstraint>& extra_constraints = {});

}  // namespace drapelab::runner
