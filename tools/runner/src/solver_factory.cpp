#include "drapelab/runner/solver_factory.hpp"

#include <stdexcept>

#include "drapelab/bullet/bullet_deformable_solver.hpp"
#include "drapelab/bullet/bullet_host.hpp"
#include "drapelab/bullet/bullet_softbody_solver.hpp"
#include "drapelab/mujoco/mujoco_solver.hpp"
#include "drapelab/spring_damper_solver.hpp"

namespace drapelab::runner {
namespace {

// Our spring-damper cloth: bare, or a plugin in a Bullet world of its own (the default).
std::unique_ptr<Solver> make_spring_damper(const scene::Scene& scene, const scene::SolverSpec& spec,
                                           std::shared_ptr<const ClothModel> model,
                                           const ClothState& initial, const World& world) {
  SpringDamperSettings settings;
  static_cast<World&>(settings) = world;
  settings.integrator = spec.integrator;
  settings.max_speed = spec.max_speed;
  settings.implicit = spec.implicit;
  settings.vbd = spec.vbd;
  settings.adaptive_substeps = spec.adaptive_substeps;
  if (!spec.bullet_host)
    return std::make_unique<SpringDamperSolver>(spec.name, std::move(model), initial, settings);
  // Hosted: the solver's contacts read the poses the host's Bullet bodies hold (a table the host
  // fills before every substep), not collider_pose(t); the world's `contacts`, which the metrics
  // use, keep the analytic poses.
  auto poses = std::make_shared<ColliderPoseTable>(scene.colliders.size());
  poses->set_substep(0.0, 0.0);  // the scene's poses until the host's first substep
  for (std::size_t c = 0; c < scene.colliders.size(); ++c) {
    ColliderSubstepMotion still;
    still.start = still.end = collider_pose(scene.colliders[c], 0.0);
    poses->set(c, still);
  }
  if (world.attachments && world.attachments->any_on_dynamic()) {
    // Particles attached to a dynamic collider follow the host's body.
    auto attachments = std::make_shared<Attachments>(*world.attachments);
    attachments->poses = poses;
    settings.attachments = std::move(attachments);
  }
  // Soft constraints ending on a dynamic collider follow the host's body too.
  settings.constraints = constraints_on_own_bodies(settings.constraints, poses);
  if (world.contacts)
    settings.contacts = std::make_shared<const ContactModel>(
        world.contacts->colliders(), world.contacts->parameters(), world.contacts->query().radius(),
        poses);
  auto guest = std::make_unique<SpringDamperSolver>(spec.name, std::move(model), initial, settings);
  return bullet::host_in_bullet_world(std::move(guest), std::move(poses), scene.colliders,
                                      scene.gravity, spec.collider_margin);
}

// Bullet's classic cloth on the scene's colliders (docs/bullet.md, "Fairness table").
std::unique_ptr<Solver> make_classic_cloth(const scene::Scene& scene, const scene::SolverSpec& spec,
                                           std::shared_ptr<const ClothModel> model,
                                           const ClothState& initial, const World& world) {
  bullet::BulletSoftBodyOptions options;
  static_cast<World&>(options) = world;
  options.dt = spec.dt;
  options.iterations = spec.iterations;
  options.margin = spec.margin;
  options.voxel_size = spec.voxel_size;
  options.collider_margin = spec.collider_margin;
  options.raw_link_stiffness = spec.link_stiffness;
  options.max_speed = spec.max_speed;
  return bullet::make_bullet_softbody_solver(spec.name, std::move(model), initial, scene.colliders,
                                             options);
}

// Bullet's deformable-world cloth on the scene's colliders.
std::unique_ptr<Solver> make_deformable_cloth(const scene::Scene& scene,
                                              const scene::SolverSpec& spec,
                                              std::shared_ptr<const ClothModel> model,
                                              const ClothState& initial, const World& world) {
  bullet::BulletDeformableOptions options;
  static_cast<World&>(options) = world;
  options.dt = spec.dt;
  options.margin = spec.margin;
  options.voxel_size = spec.voxel_size;
  options.collider_margin = spec.collider_margin;
  options.max_speed = spec.max_speed;
  return bullet::make_bullet_deformable_solver(spec.name, std::move(model), initial,
                                               scene.colliders, options);
}

// MuJoCo's cloth on the scene's colliders (docs/mujoco.md).
std::unique_ptr<Solver> make_mujoco_cloth(const scene::Scene& scene, const scene::SolverSpec& spec,
                                          std::shared_ptr<const ClothModel> model,
                                          const ClothState& initial, const World& world) {
  mujoco::MujocoOptions options;
  static_cast<World&>(options) = world;
  options.dt = spec.dt;
  options.particle_radius = spec.margin;
  options.numerics = spec.mujoco;
  options.max_speed = spec.max_speed;
  return mujoco::make_mujoco_solver(spec.name, std::move(model), initial, scene.colliders, options);
}

}  // namespace

std::unique_ptr<Solver> make_solver(const scene::Scene& scene, const scene::SolverSpec& spec,
                                    std::shared_ptr<const ClothModel> model,
                                    const ClothState& initial, const World& world) {
  // The cloth as this solver runs it: the continuum's elements for our solver with model:
  // continuum, the springs for the others.
  model = scene::cloth_for_solver(scene, spec, std::move(model));
  switch (spec.type) {
    case SolverType::spring_damper:
      return make_spring_damper(scene, spec, std::move(model), initial, world);
    case SolverType::bullet_softbody:
      return make_classic_cloth(scene, spec, std::move(model), initial, world);
    case SolverType::bullet_deformable:
      return make_deformable_cloth(scene, spec, std::move(model), initial, world);
    case SolverType::mujoco:
      return make_mujoco_cloth(scene, spec, std::move(model), initial, world);
  }
  // Every type has a case above, so reaching here is a programming error.
  throw std::logic_error(std::string("solver type '") + solver_type_name(spec.type) +
                         "' has no implementation");
}

}  // namespace drapelab::runner
