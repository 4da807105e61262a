// A scene's MuJoCo solver entry (docs/mujoco.md): its defaults as the loader resolves them, and
// what the mapping does not carry refused at the solver's line with exit-code-2 errors.
#include <gtest/gtest.h>

#include <string>

#include "drapelab/mujoco/mujoco_mapping.hpp"
#include "drapelab/scene/scene_loader.hpp"
#include "fixtures/scene_text.hpp"

namespace drapelab {
namespace {

// A 9 x 9 sheet over a sphere; the solvers' list is the last item.
std::string scene_with(const std::string& colliders, const std::string& solvers) {
  return "name: mujoco_scene\n"     // 1
         "duration: 0.1\n"          // 2
         "cloth:\n"                 // 3
         "  shape: grid\n"          // 4
         "  size: [0.4, 0.4]\n"     // 5
         "  resolution: [9, 9]\n"   // 6
         "  plane: xz\n"            // 7
         "  center: [0, 0.6, 0]\n"  // 8
         "  mass: 0.05\n"           // 9
         "  thickness: 0.004\n"     // 10
         "contact:\n"               // 11
         "  stiffness: 800\n"       // 12
         "  damping: 0.1\n"         // 13
         "colliders:\n" +           // 14
         colliders +
         "solvers:\n" + solvers;
}

const std::string kBall =
    "  - {name: ball, type: sphere, center: [0, 0.3, 0], radius: 0.2}\n";  // line 15

TEST(MujocoScene, DefaultsAreTheThicknessTheFrictionRatioAndAContactPerParticle) {
  const auto result = scene::load_scene_text(scene_with(kBall, "  - {name: mj, type: mujoco}\n"),
                                             "mujoco_scene.yaml");
  ASSERT_LOADS(result);
  const scene::SolverSpec& spec = result.scene->solvers.at(0);
  EXPECT_EQ(spec.type, SolverType::mujoco);
  EXPECT_DOUBLE_EQ(spec.margin, 0.004);  // the particles' radius: the cloth's thickness
  EXPECT_EQ(spec.mujoco.max_contacts, 81 + 64);
  EXPECT_DOUBLE_EQ(spec.mujoco.impratio,
                   mujoco::friction_impratio(0.1, mujoco::mean_free_mass(*result.model), spec.dt));
  EXPECT_GT(spec.mujoco.impratio, 1.0);
  EXPECT_EQ(spec.mujoco.constraint_solver, mujoco::ConstraintSolver::automatic);
  EXPECT_NE(spec.note.find("contact springs"), std::string::npos) << spec.note;
}

TEST(MujocoScene, GivenNumericsAreKept) {
  const auto result = scene::load_scene_text(
      scene_with(kBall,
                 "  - {name: mj, type: mujoco, constraint_solver: cg, solver_iterations: 20,\n"
                 "     tolerance: 1e-8, impratio: 3, max_contacts: 40, margin: 0.002}\n"),
      "mujoco_scene.yaml");
  ASSERT_LOADS(result);
  const scene::SolverSpec& spec = result.scene->solvers.at(0);
  EXPECT_EQ(spec.mujoco.constraint_solver, mujoco::ConstraintSolver::cg);
  EXPECT_EQ(spec.mujoco.solver_iterations, 20);
  EXPECT_DOUBLE_EQ(spec.mujoco.tolerance, 1e-8);
  EXPECT_DOUBLE_EQ(spec.mujoco.impratio, 3.0);
  EXPECT_EQ(spec.mujoco.max_contacts, 40);
  EXPECT_DOUBLE_EQ(spec.margin, 0.002);
}

TEST(MujocoScene, MeshColliderIsRefusedAtTheSolver) {
  const std::string mesh =
      "  - {name: box, type: mesh, center: [0, 0.2, 0], file: " DRAPELAB_SOURCE_DIR
      "/scenes/meshes/box_040x020x040.obj}\n";
  const auto result = scene::load_scene_text(
      scene_with(mesh, "  - {name: ours, type: spring_damper}\n  - {name: mj, type: mujoco}\n"),
      "mujoco_scene.yaml");
  EXPECT_TRUE(fixtures::HasError(
      result, fixtures::at_line("mujoco_scene.yaml", 18),
      {"solvers.1.type", "is mujoco", "collider 'box' is a mesh", "convex hull"}));
}

TEST(MujocoScene, DynamicColliderIsRefusedAtTheSolver) {
  const std::string ball =
      "  - {name: ball, type: sphere, center: [0, 0.3, 0], radius: 0.2, dynamic: {mass: 1}}\n";
  const auto result = scene::load_scene_text(scene_with(ball, "  - {name: mj, type: mujoco}\n"),
                                             "mujoco_scene.yaml");
  EXPECT_TRUE(fixtures::HasError(result, fixtures::at_line("mujoco_scene.yaml", 17),
                                 {"solvers.0.type", "collider 'ball' is dynamic"}));
}

TEST(MujocoScene, AClothTooLargeForMujocosStackIsRefused) {
  const auto result = scene::load_scene_text(scene_with(kBall, "  - {name: mj, type: mujoco}\n"),
                                             "mujoco_scene.yaml", {"cloth.resolution=[300, 300]"});
  EXPECT_TRUE(fixtures::HasError(result, fixtures::at_line("mujoco_scene.yaml", 17),
                                 {"solvers.0.type", "90001 bodies", "2^31", "fewer particles"}));
}

TEST(MujocoScene, BulletKeysAreNotMujocos) {
  const auto result = scene::load_scene_text(
      scene_with(kBall, "  - {name: mj, type: mujoco, voxel_size: 0.001}\n"), "mujoco_scene.yaml");
  EXPECT_FALSE(result.ok());
  EXPECT_NE(fixtures::all_errors(result).find("voxel_size"), std::string::npos)
      << fixtures::all_errors(result);
}

}  // namespace
}  // namespace drapelab
