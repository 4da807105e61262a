#include "solver_factory.hpp"

#include <stdexcept>

#include "drapelab/bullet/bullet_deformable_solver.hpp"
#include "drapelab/bullet/bullet_host.hpp"
#include "drapelab/bullet/bullet_softbody_solver.hpp"
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
    settings.implicit = spec.implicit;
    auto solver = std::make_unique<SpringDamperSolver>(spec.name, std::move(model), initial, settings);
    if (!spec.bullet_host) return solver;
    return bullet::host_in_bullet_world(std::move(solver), scene.colliders, scene.gravity);
  }
  if (spec.type == "bullet_softbody") {
    bullet::BulletSoftBodyOptions options;
    options.dt = spec.dt;
    options.iterations = spec.iterations;
    options.margin = spec.margin;
    options.voxel_size = spec.voxel_size;
    options.collider_margin = spec.collider_margin;
    options.raw_link_stiffness = spec.link_stiffness;
    options.gravity = scene.gravity;
    options.air_damping = scene.cloth.air_damping;
    options.max_speed = spec.max_speed;
    return bullet::make_bullet_softbody_solver(spec.name, std::move(model), initial, scene.colliders, options);
  }
  if (spec.type == "bullet_deformable") {
    bullet::BulletDeformableOptions options;
    options.dt = spec.dt;
    options.margin = spec.margin;
    options.voxel_size = spec.voxel_size;
    options.collider_margin = spec.collider_margin;
    options.gravity = scene.gravity;
    options.air_damping = scene.cloth.air_damping;
    options.max_speed = spec.max_speed;
    return bullet::make_bullet_deformable_solver(spec.name, std::move(model), initial, scene.colliders, options);
  }
  // The loader knows no other type, so reaching here is a programming error.
  throw std::logic_error("solver type '" + spec.type + "' has no implementation");
}

}  // namespace drapelab::runner
