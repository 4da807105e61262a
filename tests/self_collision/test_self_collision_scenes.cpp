// Self-collision and contact on triangles on whole scenes, run as `drapelab run` steps our solver
// (runner/simulate_solver.hpp) and audited every recorded frame: a heap on the floor under every
// integrator, a sheet folded over a rod, and colliders' rims and edges under draped cloth.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "fixtures/drape_scenes.hpp"
#include "scene_audit.hpp"

namespace drapelab {
namespace {

using Audit = fixtures::SceneAudit;

Audit run_audited(const std::string& text, const std::string& name,
                  const std::vector<std::string>& overrides) {
  return fixtures::audit_scene_text(text, name, overrides);
}

// scenes/heap.yaml's sheet and settings, our solver only, 1.2 s (the heap has formed by 0.8 s).
const std::string kHeap = R"(name: heap_test
duration: 1.2
frame_rate: 25
seed: 4
cloth:
  shape: grid
  size: [0.8, 0.8]
  resolution: [33, 33]
  plane: xy
  center: [0, 0.405, 0]
  rotation: [6, 0, 0]
  areal_density: 0.15
  thickness: 0.004
  perturbation: 0.002
  springs:
    stretch: {ks: 600, kd: 0.02}
    shear:   {ks: 60,  kd: 0.005}
    bend:    {ks: 0.5, kd: 0.0005}
  air_damping: 1.0
  self_collision: {enabled: true, thickness: 0.004, stiffness: 300, damping: 0.005, friction: 0.4}
colliders:
  - {name: floor, type: plane, point: [0, 0, 0], normal: [0, 1, 0], friction: 0.5}
contact: {stiffness: 1000, damping: 0.1}
solvers:
  - {name: ours, type: spring_damper, integrator: symplectic_euler, dt: 1.25e-4}
)";

// Each integrator named, if it stays stable at the scene's step, keeps the heap free of crossings
// at every frame; symplectic Euler and implicit Euler must stay stable.
void expect_heap_free_of_crossings(const std::vector<std::string>& integrators) {
  for (const std::string& integrator : integrators) {
    SCOPED_TRACE(integrator);
    const Audit audit =
        run_audited(kHeap, "heap_test.yaml", {"solvers.0.integrator=" + integrator});
    const bool must_be_stable = integrator == "symplectic_euler" || integrator == "implicit_euler";
    if (audit.result.status != SolverStatus::ok) {
      EXPECT_FALSE(must_be_stable) << audit.result.message;
      continue;
    }
    EXPECT_EQ(audit.most_crossings, 0);
    EXPECT_LT(audit.final_lowest, 0.01);  // it has fallen into a heap on the floor
  }
}

// Every integrator (slow: a minute of CPU; the next test is its CI-sized twin).
TEST(SelfCollisionScenes, AHeapNeverCrossesItselfUnderAnyStableIntegrator) {
  expect_heap_free_of_crossings({"symplectic_euler", "explicit_euler", "midpoint", "rk4", "verlet",
                                 "leapfrog", "implicit_euler"});
}

// The two that must stay stable and the two cheapest of the others (about 32 s of CPU).
TEST(SelfCollisionScenesCi, AHeapNeverCrossesItselfUnderFourIntegrators) {
  expect_heap_free_of_crossings({"symplectic_euler", "implicit_euler", "verlet", "leapfrog"});
}

// A 0.6 m sheet dropped off-centre across a horizontal rod: both halves hang, the longer one
// swinging past the shorter, and no edge ever crosses the cloth.
TEST(SelfCollisionScenes, ASheetFoldedOverARodNeverCrossesItself) {
  const std::string rod = R"(name: rod_fold
duration: 1.5
frame_rate: 20
cloth:
  shape: grid
  size: [0.6, 0.3]
  resolution: [31, 16]
  plane: xz
  center: [0.07, 0.52, 0]
  areal_density: 0.15
  thickness: 0.004
  springs:
    stretch: {ks: 600, kd: 0.02}
    shear:   {ks: 60,  kd: 0.005}
    bend:    {ks: 0.2, kd: 0.0002}
  air_damping: 0.5
  self_collision: {enabled: true, thickness: 0.004, stiffness: 300, damping: 0.005, friction: 0.3}
colliders:
  - {name: rod, type: cylinder, center: [0, 0.5, 0], radius: 0.012, height: 0.6, axis: [0, 0, 1]}
contact: {stiffness: 1000, damping: 0.1, friction: 0.5}
solvers:
  - {name: ours, type: spring_damper, integrator: symplectic_euler, dt: 1.25e-4}
)";
  const Audit audit = run_audited(rod, "rod_fold.yaml", {});
  ASSERT_EQ(audit.result.status, SolverStatus::ok) << audit.result.message;
  EXPECT_EQ(audit.most_crossings, 0);
  EXPECT_LT(audit.final_lowest, 0.5 - 0.2);  // the halves hang well below the rod
}

// The Cusick drape of docs/validation.md V10 (fixtures/drape_scenes.hpp), its rim between two rings
// of the disc, with contact on triangles:
// at rest the support's rim stays out of the cloth's triangles (their thickness included); without
// it the rim cuts between the particles.
TEST(TriangleContact, TheCusickRimStaysOutOfTheClothsTriangles) {
  const Audit on =
      run_audited(fixtures::cusick_v10_scene(false), "cusick_rim.yaml", {"contact.triangles=true"});
  ASSERT_EQ(on.result.status, SolverStatus::ok) << on.result.message;
  EXPECT_LE(on.final_penetration, 0.001);
  EXPECT_GE(on.final_penetration, 0.0);
  const Audit off = run_audited(fixtures::cusick_v10_scene(false), "cusick_rim.yaml",
                                {"contact.triangles=false"});
  ASSERT_EQ(off.result.status, SolverStatus::ok) << off.result.message;
  EXPECT_GT(off.final_penetration, 0.001);
}

// A coarse sheet (4 cm between particles) draped over the corner of a box: the box's edges and
// corner stay out of its triangles with contact on triangles, and cut into them without.
TEST(TriangleContact, ABoxEdgeStaysOutOfACoarseSheet) {
  const std::string box = R"(name: box_edge
duration: 1.0
frame_rate: 10
cloth:
  shape: grid
  size: [0.4, 0.4]
  resolution: [11, 11]
  plane: xz
  center: [0.13, 0.41, 0.13]
  areal_density: 0.2
  thickness: 0.003
  springs:
    stretch: {ks: 500, kd: 0.02}
    shear:   {ks: 50,  kd: 0.005}
    bend:    {ks: 1,   kd: 0.001}
  air_damping: 4
colliders:
  - {name: block, type: box, center: [0, 0.2, 0], half_extents: [0.2, 0.2, 0.2], friction: 0.6}
contact: {stiffness: 500, damping: 0.05}
solvers:
  - {name: ours, type: spring_damper, integrator: symplectic_euler}
)";
  const Audit on = run_audited(box, "box_edge.yaml", {"contact.triangles=true"});
  ASSERT_EQ(on.result.status, SolverStatus::ok) << on.result.message;
  EXPECT_LE(on.final_penetration, 0.003);
  const Audit off = run_audited(box, "box_edge.yaml", {"contact.triangles=false"});
  ASSERT_EQ(off.result.status, SolverStatus::ok) << off.result.message;
  EXPECT_GT(off.final_penetration, 0.003);
}

}  // namespace
}  // namespace drapelab
