// The world every solver of a run simulates (drapelab/world.hpp), built once from the scene by the
// runner (runner::build_world) and shared by every solver kind.
#include <gtest/gtest.h>

#include <string>

#include "drapelab/runner/scene_setup.hpp"
#include "drapelab/runner/solver_factory.hpp"
#include "drapelab/scene/scene_loader.hpp"

namespace drapelab {
namespace {

const std::string kText = R"(name: windy_drape
duration: 0.04
frame_rate: 50
gravity: [0.0, -9.0, 0.5]
cloth:
  shape: grid
  size: [0.4, 0.4]
  resolution: [9, 9]
  center: [0.0, 0.3, 0.0]
  mass: 0.05
  air_damping: 0.2
  self_collision: {enabled: true}
  pins:
    - {within: {center: [-0.2, 0.3, -0.2], radius: 0.01}, attach: post}
constraints:
  - {type: distance, a: [4, 4], b: {point: [0.0, 0.1, 0.0]}, length: 0.1, mode: soft, stiffness: 20, damping: 0.1}
air: {wind: [1.0, 0.0, 0.0]}
contact: {triangles: true}
colliders:
  - {name: post, type: box, center: [-0.2, 0.2, -0.2], half_extents: [0.02, 0.1, 0.02]}
solvers:
  - {name: ours, type: spring_damper, dt: 0.0005}
  - {name: classic, type: bullet_softbody}
  - {name: deformable, type: bullet_deformable}
)";

TEST(World, HoldsWhatTheSceneSimulatesOnce) {
  const auto loaded = scene::load_scene_text(kText, "windy_drape.yaml", {});
  ASSERT_TRUE(loaded.ok()) << (loaded.errors.empty() ? "" : loaded.errors.front());
  const scene::Scene& scene = *loaded.scene;
  const runner::SceneSetup setup = runner::build_scene_setup(scene, loaded.model);
  ASSERT_TRUE(setup.world);
  const World& world = *setup.world;
  EXPECT_EQ(world.gravity, scene.gravity);
  EXPECT_EQ(world.air_damping, 0.2);
  EXPECT_TRUE(world.air.enabled);
  EXPECT_EQ(world.air.wind, Eigen::Vector3d(1.0, 0.0, 0.0));
  EXPECT_TRUE(world.self_collision.enabled);
  EXPECT_TRUE(world.collider_edges);
  // The colliders' contact is the one the metrics measure with, not a copy.
  EXPECT_EQ(world.contacts, setup.contacts);
  ASSERT_TRUE(world.attachments);
  EXPECT_EQ(world.attachments->list.size(), 1u);
  ASSERT_TRUE(world.constraints);
  EXPECT_EQ(world.constraints, setup.constraints);
  EXPECT_TRUE(world.constraints->has_soft());
}

TEST(World, EverySolverKindRunsFromTheSameWorld) {
  const auto loaded = scene::load_scene_text(kText, "windy_drape.yaml", {});
  ASSERT_TRUE(loaded.ok()) << (loaded.errors.empty() ? "" : loaded.errors.front());
  const scene::Scene& scene = *loaded.scene;
  const runner::SceneSetup setup = runner::build_scene_setup(scene, loaded.model);
  for (const scene::SolverSpec& spec : scene.solvers) {
    auto solver = runner::make_solver(scene, spec, setup.model, setup.initial, *setup.world);
    for (int k = 0; k < spec.steps_per_frame; ++k) solver->step(spec.dt);
    EXPECT_EQ(solver->status(), SolverStatus::ok) << spec.name << ": " << solver->message();
    // The pin rides its post: it stays where the world placed it (the post is still).
    const int pinned = setup.world->attachments->list.front().particle;
    EXPECT_LT((solver->state().x.col(pinned) - setup.initial.x.col(pinned)).norm(), 1e-9)
        << spec.name;
  }
}

// The viewer's drag is added to the scene's constraints for the solvers it builds; the scene's
// own world is left as it was.
TEST(World, ADragJoinsACopyOfTheConstraints) {
  const auto loaded = scene::load_scene_text(kText, "windy_drape.yaml", {});
  ASSERT_TRUE(loaded.ok());
  const scene::Scene& scene = *loaded.scene;
  const runner::SceneSetup setup = runner::build_scene_setup(scene, loaded.model);
  DistanceConstraint drag;
  drag.a = 3;
  drag.b.kind = ConstraintEnd::Kind::point;
  drag.length = 0.05;
  drag.mode = ConstraintMode::soft;
  drag.stiffness = 5.0;
  const auto dragged =
      runner::build_world(scene, setup.initial, setup.contacts, setup.constraints, {drag});
  EXPECT_EQ(dragged->constraints->list.size(), setup.constraints->list.size() + 1);
  EXPECT_EQ(setup.world->constraints->list.size(), setup.constraints->list.size());
}

}  // namespace
}  // namespace drapelab
