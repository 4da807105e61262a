#include "solver_factory.hpp"

#include <stdexcept>

#include "drapelab/spring_damper_solver.hpp"

namespace drapelab::runner {

std::unique_ptr<Solver> make_solver(const scene::Scene& scene, const scene::SolverSpec& spec,
                                    std::shared_ptr<const ClothModel> model, const ClothState& initial,
                                    std::shared_ptr<const ContactModel> contacts) {
  if (spec.type == "spring_damper") {
    SpringDamperSettings settings;
    settings.integrator = spec.integrator;
    settings.gravity = scene.gravity;
    settings.air_damping = scene.cloth.air_damping;
    settings.max_speed = spec.max_speed;
    settings.contacts = std::move(contacts);
    return std::make_unique<SpringDamperSolver>(spec.name, std::move(model), initial, settings);
  }
  // The loader refuses every other type in this version, so reaching here is a programming error.
  throw std::logic_error("solver type '" + spec.type + "' has no implementation");
}

}  // namespace drapelab::runner
