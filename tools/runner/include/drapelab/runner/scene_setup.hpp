// What every solver of a scene starts from: the model, the initial state and the colliders' contact
// model. Built once per scene by run_scene and by the in-process simulations (simulate_solver.hpp),
// so both start every solver from exactly the same cloth.
#pragma once

#include <memory>
#include <string>

#include "drapelab/cloth_metrics.hpp"
#include "drapelab/cloth_model.hpp"
#include "drapelab/cloth_state.hpp"
#include "drapelab/contact_model.hpp"
#include "drapelab/drape_metrics.hpp"
#include "drapelab/scene/scene.hpp"
#include "drapelab/self_intersections.hpp"
#include "drapelab/world.hpp"

namespace drapelab::runner {

struct SceneSetup {
  std::shared_ptr<const ClothModel> model;
  ClothState initial;                            // rest positions plus the seeded perturbation
  std::shared_ptr<const ContactModel> contacts;  // null when the scene has no colliders
  std::shared_ptr<const DrapeMeter> drape;       // null without metrics.drape_support
  std::shared_ptr<const SelfIntersectionCounter> self_intersections;  // the model's edges, once
  std::shared_ptr<const DistanceConstraints> constraints;  // null when the scene has none
  // What every solver simulates (build_world from the state above), built once and shared.
  std::shared_ptr<const World> world;
};

// The world every solver of `scene` simulates from `initial` (world.hpp): gravity, air damping and
// air, the colliders' contact (`contacts`, null without colliders), self-collision, the pins
// carried by colliders (placed from `initial`), and the scene's distance constraints
// (`constraints`) with `extra_constraints` added (the viewer's live drag).
std::shared_ptr<const World> build_world(
    const scene::Scene& scene, const ClothState& initial,
    std::shared_ptr<const ContactModel> contacts,
    std::shared_ptr<const DistanceConstraints> constraints,
    const std::vector<DistanceConstraint>& extra_constraints = {});

// Builds the cloth (any shape) unless `model` is given (the loader's, scene::LoadResult::model,
// built from this very scene), its initial state (scene.cloth.perturbation, scene.seed), the
// contact model (scene.contact, the cloth's thickness as the particles' radius) and the drape
// meter.
SceneSetup build_scene_setup(const scene::Scene& scene,
                             std::shared_ptr<const ClothModel> model = nullptr);

// The per-frame metrics of a state that need no colliders: ClothMetrics, plus the drape coefficient
// and node count when the scene names a drape support.
ClothMetrics frame_metrics(const SceneSetup& setup, const scene::Scene& scene,
                           const ClothState& state);

// "the stretch spring between particle a (grid i, j) and particle b (...) is stretched by s": the
// most stretched stretch spring of `state` (strain |x_a - x_b| / L - 1), for unstable-run messages.
std::string describe_most_stretched_spring(const ClothModel& model, const ClothState& state);

}  // namespace drapelab::runner
