// Bullet's cloths on mesh colliders: which shape each meets a concave mesh as, and where each
// cloth comes to rest in a concave notch (tests/bullet/scenes/cloth_in_channel.yaml).
#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <string>
#include <vector>

#include "contact/scene_runs.hpp"
#include "drapelab/bullet/parameter_mapping.hpp"
#include "drapelab/runner/scene_setup.hpp"
#include "drapelab/runner/solver_factory.hpp"
#include "drapelab/scene/scene_loader.hpp"

namespace drapelab {
namespace {

using scene_runs::run_scene;
using scene_runs::SceneRun;

constexpr char kChannel[] = "tests/bullet/scenes/cloth_in_channel.yaml";
constexpr double kNotchFloor = 0.1;   // m, the channel's notch; its top is at 0.2 m
constexpr double kThickness = 0.005;  // m, the scene's cloth

// The mesh of a scene's collider (the scene is kept, with its mesh, to the end of the tests).
const TriangleMesh& collider_mesh(const std::string& scene_path, const char* collider,
                                  const std::vector<std::string>& overrides = {}) {
  static std::deque<scene::Scene> kept;
  const auto loaded =
      scene::load_scene_file(std::string(DRAPELAB_SOURCE_DIR) + "/" + scene_path, overrides);
  EXPECT_TRUE(loaded.ok());
  kept.push_back(*loaded.scene);
  for (const Collider& c : kept.back().colliders)
    if (c.name == collider) return *c.mesh;
  ADD_FAILURE() << "no collider " << collider;
  return *kept.back().colliders.front().mesh;
}

SceneRun run_channel(const std::string& type) {
  return run_scene(kChannel, {"solvers=[{name: s, type: " + type + "}]"});
}

TEST(BulletMesh, ConvexPartsAreToldFromConcaveOnes) {
  // The round table's top, column and base are convex, as is the icosphere; the channel and the
  // mannequin are not.
  EXPECT_TRUE(bullet::mesh_parts_are_convex(collider_mesh("scenes/round_table.yaml", "table")));
  EXPECT_TRUE(bullet::mesh_parts_are_convex(
      collider_mesh("tests/contact/scenes/sphere_mesh_drape.yaml", "ball",
                    {"colliders=[{name: ball, type: mesh, file: ../../../scenes/meshes/"
                     "icosphere_r015.obj, center: [0, 0.5, 0]}]"})));
  EXPECT_FALSE(bullet::mesh_parts_are_convex(collider_mesh(kChannel, "channel")));
  EXPECT_FALSE(
      bullet::mesh_parts_are_convex(collider_mesh("scenes/mannequin_tshirt.yaml", "mannequin")));
}

// The deformable cloth meets the concave mesh by face contacts against its triangles: it lands on
// the notch's floor, as ours does, one collider margin (1 mm) higher.
TEST(BulletMesh, TheDeformableClothLandsInAConcaveNotch) {
  const SceneRun ours = run_channel("spring_damper");
  const SceneRun deformable = run_channel("bullet_deformable");
  EXPECT_NEAR(ours.result.final_metrics.centroid.y(), kNotchFloor + kThickness, 0.001);
  EXPECT_NEAR(deformable.result.final_metrics.centroid.y(), kNotchFloor + kThickness, 0.003);
  EXPECT_NEAR(deformable.result.final_metrics.lowest_y, kNotchFloor + kThickness, 0.003);
}

// The face contacts' impulses are the mesh's contact force: at rest in the notch they carry the
// sheet's weight (measured: 0.191 to 0.195 N of 0.196 N over the last frames, the sheet still
// creeping on the floor).
TEST(BulletMesh, TheDeformableClothsFaceContactsCarryItsWeight) {
  const auto loaded = scene::load_scene_file(std::string(DRAPELAB_SOURCE_DIR) + "/" + kChannel,
                                             {"solvers=[{name: s, type: bullet_deformable}]"});
  ASSERT_TRUE(loaded.ok());
  const scene::Scene& scene = *loaded.scene;
  const runner::SceneSetup setup = runner::build_scene_setup(scene, loaded.model);
  const auto solver =
      runner::make_solver(scene, scene.solvers.front(), setup.model, setup.initial, *setup.world);
  const double h = scene.solvers.front().dt;  // s
  double normal = 0.0;                        // N, mean over the last 0.1 s
  const int steps = static_cast<int>(std::lround(scene.duration / h));
  const int window = static_cast<int>(std::lround(0.1 / h));
  for (int k = 0; k < steps; ++k) {
    solver->step(h);
    if (k >= steps - window) normal += solver->collider_forces().at(0).normal / window;
  }
  ASSERT_EQ(solver->status(), SolverStatus::ok) << solver->message();
  const double weight = setup.model->total_mass() * 9.81;  // N
  EXPECT_NEAR(normal, weight, 0.05 * weight);
}

// The classic cloth's signed-distance cache meets only convex shapes, so it meets the channel as
// its hull and stops on the hull's top, across the notch (docs/bullet.md, "Mesh colliders").
TEST(BulletMesh, TheClassicClothStopsOnAConcaveMeshsHull) {
  const SceneRun classic = run_channel("bullet_softbody");
  EXPECT_NEAR(classic.result.final_metrics.centroid.y(), 2 * kNotchFloor + kThickness, 0.003);
}

}  // namespace
}  // namespace drapelab
