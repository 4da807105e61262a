#include "drapelab/runner/scene_setup.hpp"

#include "drapelab/scene/number_format.hpp"

namespace drapelab::runner {
namespace {

// Up, against gravity (y without gravity): the drape shadow is cast along it.
Eigen::Vector3d up_of(const scene::Scene& scene) {
  return scene.gravity.squaredNorm() > 0.0 ? Eigen::Vector3d(-scene.gravity)
                                           : Eigen::Vector3d::UnitY();
}

}  // namespace

SceneSetup build_scene_setup(const scene::Scene& scene, std::shared_ptr<const ClothModel> model) {
  SceneSetup setup;
  setup.model = model ? std::move(model)
                      : std::make_shared<const ClothModel>(scene::build_scene_cloth(scene));
  setup.initial = scene::initial_scene_state(scene, *setup.model);
  if (!scene.colliders.empty())
    setup.contacts = std::make_shared<const ContactModel>(
        scene.colliders, ContactParameters{scene.contact.stiffness, scene.contact.damping},
        setup.model->thickness);
  setup.self_intersections =
      std::make_shared<const SelfIntersectionCounter>(setup.model->triangles);
  setup.constraints = scene::scene_constraints(scene);
  setup.world = build_world(scene, setup.initial, setup.contacts, setup.constraints);
  if (scene.drape_support)
    setup.drape =
        std::make_shared<const DrapeMeter>(*setup.model, scene.drape_support->disc, up_of(scene));
  return setup;
}

std::shared_ptr<const World> build_world(const scene::Scene& scene, const ClothState& initial,
                                         std::shared_ptr<const ContactModel> contacts,
                                         std::shared_ptr<const DistanceConstraints> constraints,
                                         const std::vector<DistanceConstraint>& extra_constraints) {
  auto world = std::make_shared<World>();
  world->gravity = scene.gravity;
  world->air_damping = scene.cloth.air_damping;
  world->contacts = std::move(contacts);
  world->collider_edges = scene.contact.triangles;
  world->self_collision = scene.cloth.self_collision;
  world->attachments = scene::scene_attachments(scene, initial);
  if (!extra_constraints.empty()) {
    auto all = constraints ? std::make_shared<DistanceConstraints>(*constraints)
                           : std::make_shared<DistanceConstraints>();
    all->colliders = scene.colliders;
    all->list.insert(all->list.end(), extra_constraints.begin(), extra_constraints.end());
    constraints = std::move(all);
  }
  world->constraints = std::move(constraints);
  world->air = scene.air;
  return world;
}

ClothMetrics frame_metrics(const SceneSetup& setup, const scene::Scene& scene,
                           const ClothState& state) {
  ClothMetrics metrics = compute_cloth_metrics(*setup.model, state, scene.gravity);
  if (setup.drape) {
    const DrapeMeasure drape = setup.drape->measure(*setup.model, state.x);
    metrics.drape_coefficient = drape.coefficient;
    metrics.drape_nodes = drape.nodes;
  }
  return metrics;
}

std::string describe_most_stretched_spring(const ClothModel& model, const ClothState& state) {
  const SpringSet& s = model.springs;
  std::size_t worst = 0;
  double worst_strain = -1.0;
  for (std::size_t e = 0; e < s.size(); ++e) {
    if (s.kind[e] != SpringKind::stretch) continue;
    const double strain =
        (state.x.col(s.v0[e]) - state.x.col(s.v1[e])).norm() / s.rest_length[e] - 1.0;
    if (strain > worst_strain) {
      worst_strain = strain;
      worst = e;
    }
  }
  return "the stretch spring between " + model.describe_particle(s.v0[worst]) + " and " +
         model.describe_particle(s.v1[worst]) + " is stretched by " + format_number(worst_strain);
}

}  // namespace drapelab::runner
