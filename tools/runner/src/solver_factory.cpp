#include "drapelab/runner/solver_factory.hpp"

#include <stdexcept>

#include "drapelab/bullet/bullet_deformable_solver.hpp"
#include "drapelab/bullet/bullet_host.hpp"
#include "drapelab/bullet/bullet_softbody_solver.hpp"
#include "drapelab/spring_damper_solver.hpp"

namespace drapelab::runner {
namespace {

// What the scene holds the cloth by besides its pins, built once per solver.
struct Holds {
  std::shared_ptr<const Attachments> attachments;          // null: no pin moves with a collider
  std::shared_ptr<const DistanceConstraints> constraints;  // null: no constraint
};

// Our spring-damper cloth: bare, or a plugin in a Bullet world of its own (the default).
std::unique_ptr<Solver> make_spring_damper(const scene::Scene& scene, const scene::SolverSpec& spec,
                                           std::shared_ptr<const ClothModel> model,
                                           const ClothState& initial, const Holds& holds,
                                           std::shared_ptr<const ContactModel> contacts) {
  SpringDamperSettings settings;
  settings.integrator = spec.integrator;
  settings.gravity = scene.gravity;
  settings.air_damping = scene.cloth.air_damping;
  settings.max_speed = spec.max_speed;
  settings.implicit = spec.implicit;
  settings.vbd = spec.vbd;
  settings.adaptive_substeps = spec.adaptive_substeps;
  settings.self_collision = scene.cloth.self_collision;
  settings.collider_edges = scene.contact.triangles;
  settings.attachments = holds.attachments;
  settings.constraints = holds.constraints;
  settings.air = scene.air;
  if (!spec.bullet_host) {
    settings.contacts = std::move(contacts);
    return std::make_unique<SpringDamperSolver>(spec.name, std::move(model), initial, settings);
  }
  // Hosted: the solver's contacts read the poses the host's Bullet bodies hold (a table the host
  // fills before every substep), not collider_pose(t); the runner's `contacts`, which the metrics
  // use, keep the analytic poses.
  auto poses = std::make_shared<ColliderPoseTable>(scene.colliders.size());
  poses->set_substep(0.0, 0.0);  // the scene's poses until the host's first substep
  for (std::size_t c = 0; c < scene.colliders.size(); ++c) {
    ColliderSubstepMotion still;
    still.start = still.end = collider_pose(scene.colliders[c], 0.0);
    poses->set(c, still);
  }
  if (holds.attachments && holds.attachments->any_on_dynamic()) {
    // Particles attached to a dynamic collider follow the host's body.
    auto attachments = std::make_shared<Attachments>(*holds.attachments);
    attachments->poses = poses;
    settings.attachments = std::move(attachments);
  }
  // Soft constraints ending on a dynamic collider follow the host's body too.
  settings.constraints = constraints_on_own_bodies(settings.constraints, poses);
  if (contacts)
    settings.contacts = std::make_shared<const ContactModel>(
        contacts->colliders(), contacts->parameters(), contacts->query().radius(), poses);
  auto guest = std::make_unique<SpringDamperSolver>(spec.name, std::move(model), initial, settings);
  return bullet::host_in_bullet_world(std::move(guest), std::move(poses), scene.colliders,
                                      scene.gravity, spec.collider_margin);
}

// Bullet's classic cloth on the scene's colliders (docs/bullet.md, "Fairness table").
std::unique_ptr<Solver> make_classic_cloth(const scene::Scene& scene, const scene::SolverSpec& spec,
                                           std::shared_ptr<const ClothModel> model,
                                           const ClothState& initial, const Holds& holds) {
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
  options.self_collision = scene.cloth.self_collision;  // no effect in Bullet 3.24's classic cloth
  options.attachments = holds.attachments;
  options.constraints = holds.constraints;
  options.air = scene.air;
  return bullet::make_bullet_softbody_solver(spec.name, std::move(model), initial, scene.colliders,
                                             options);
}

// Bullet's deformable-world cloth on the scene's colliders.
std::unique_ptr<Solver> make_deformable_cloth(const scene::Scene& scene,
                                              const scene::SolverSpec& spec,
                                              std::shared_ptr<const ClothModel> model,
                                              const ClothState& initial, const Holds& holds) {
  bullet::BulletDeformableOptions options;
  options.dt = spec.dt;
  options.margin = spec.margin;
  options.voxel_size = spec.voxel_size;
  options.collider_margin = spec.collider_margin;
  options.gravity = scene.gravity;
  options.air_damping = scene.cloth.air_damping;
  options.max_speed = spec.max_speed;
  options.self_collision = scene.cloth.self_collision;
  options.attachments = holds.attachments;
  options.constraints = holds.constraints;
  options.air = scene.air;
  return bullet::make_bullet_deformable_solver(spec.name, std::move(model), initial,
                                               scene.colliders, options);
}

}  // namespace

std::unique_ptr<Solver> make_solver(const scene::Scene& scene, const scene::SolverSpec& spec,
                                    std::shared_ptr<const ClothModel> model,
                                    const ClothState& initial,
                                    std::shared_ptr<const ContactModel> contacts,
                                    const std::vector<DistanceConstraint>& extra_constraints) {
  // The cloth as this solver runs it: the continuum's elements for our solver with model:
  // continuum, the springs for the others.
  model = scene::cloth_for_solver(scene, spec, std::move(model));
  std::shared_ptr<const DistanceConstraints> constraints = scene::scene_constraints(scene);
  if (!extra_constraints.empty()) {
    auto all = constraints ? std::make_shared<DistanceConstraints>(*constraints)
                           : std::make_shared<DistanceConstraints>();
    all->colliders = scene.colliders;
    all->list.insert(all->list.end(), extra_constraints.begin(), extra_constraints.end());
    constraints = std::move(all);
  }
  const Holds holds{scene::scene_attachments(scene, initial), std::move(constraints)};
  switch (spec.type) {
    case SolverType::spring_damper:
      return make_spring_damper(scene, spec, std::move(model), initial, holds, std::move(contacts));
    case SolverType::bullet_softbody:
      return make_classic_cloth(scene, spec, std::move(model), initial, holds);
    case SolverType::bullet_deformable:
      return make_deformable_cloth(scene, spec, std::move(model), initial, holds);
  }
  // Every type has a case above, so reaching here is a programming error.
  throw std::logic_error(std::string("solver type '") + solver_type_name(spec.type) +
                         "' has no implementation");
}

}  // namespace drapelab::runner
