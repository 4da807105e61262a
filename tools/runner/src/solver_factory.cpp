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
    settings.implicit = spec.implicit;
    settings.adaptive_substeps = spec.adaptive_substeps;
    if (!spec.bullet_host) {
      settings.contacts = std::move(contacts);
      return std::make_unique<SpringDamperSolver>(spec.name, std::move(model), initial, settings);
    }
    // Hosted: the solver's contacts read the poses the host's Bullet bodies hold (a table the host
    // fills before every substep), not collider_pose(t); the runner's `contacts`, which the metrics
    // use, keep the analytic poses.
    auto poses = std::make_shared<ColliderPoseTable>(scene.colliders.size());
    if (contacts)
      settings.contacts = std::make_shared<const ContactModel>(contacts->colliders(), contacts->parameters(),
                                                               contacts->query().radius(), poses);
    auto guest = std::make_unique<SpringDamperSolver>(spec.name, std::move(model), initial, settings);
    return bullet::host_in_bullet_world(std::move(guest), std::move(poses), scene.colliders, scene.gravity,
                                        spec.collider_margin);
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
