// MuJoCo's cloth against physics with known answers (docs/mujoco.md, "Tests"): free fall is
// symplectic Euler exactly, a hanging chain rests at Hooke's statics, a sheet rests on the floor
// its weight over the contact stiffness deep and loads it with its weight, two particles rest the
// self-collision thickness apart, a particle on an incline holds below the friction angle and
// slides at g (sin - mu cos) above it, a moving box carries the cloth by friction, pins hold and
// attached pins follow their collider, and a full contact buffer stops the run with an error.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "drapelab/attachments.hpp"
#include "drapelab/contact_model.hpp"
#include "drapelab/grid_cloth.hpp"
#include "drapelab/mujoco/mujoco_solver.hpp"
#include "fixtures/chains.hpp"
#include "fixtures/colliders.hpp"
#include "fixtures/sheets.hpp"

namespace drapelab {
namespace {

constexpr double kGravity = 9.81;  // m/s^2

struct Rig {
  double dt = 1e-3;       // s
  double radius = 0.005;  // m, the particles' geoms
  ContactParameters contact{500.0, 0.5};
  double air_damping = 0.0;  // 1/s
  mujoco::MujocoSettings numerics;
  SelfCollisionSettings self_collision;
  std::shared_ptr<const Attachments> attachments;
};

Rig with_step(double dt, double air_damping = 0.0) {
  Rig rig;
  rig.dt = dt;
  rig.air_damping = air_damping;
  return rig;
}

std::unique_ptr<Solver> mujoco_cloth(const std::shared_ptr<const ClothModel>& model,
                                     const ClothState& initial, std::vector<Collider> colliders,
                                     const Rig& setup = {}) {
  mujoco::MujocoOptions options;
  options.dt = setup.dt;
  options.particle_radius = setup.radius;
  options.air_damping = setup.air_damping;
  options.numerics = setup.numerics;
  options.self_collision = setup.self_collision;
  options.attachments = setup.attachments;
  if (!colliders.empty())
    options.contacts = std::make_shared<const ContactModel>(colliders, setup.contact, setup.radius);
  return mujoco::make_mujoco_solver("mujoco", model, initial, std::move(colliders), options);
}

void run(Solver& solver, double seconds, double dt) {
  const int steps = static_cast<int>(std::lround(seconds / dt));
  for (int k = 0; k < steps; ++k) solver.step(dt);
  ASSERT_EQ(solver.status(), SolverStatus::ok) << solver.message();
}

TEST(MujocoSolver, FreeFallIsSymplecticEuler) {
  GridClothSpec spec = fixtures::bullet_test_sheet(4, 0.3, {0, 2, 0}, 0.05);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  const ClothState initial = initial_grid_state(*model, spec, 0.0, 0);
  const double h = 1.0 / 600;
  auto solver = mujoco_cloth(model, initial, {}, with_step(h));
  const int n = 300;
  for (int k = 0; k < n; ++k) solver->step(h);
  const double expected = kGravity * h * h * n * (n + 1) / 2.0;  // v += h g, then x += h v
  for (int i = 0; i < model->particle_count(); ++i) {
    EXPECT_NEAR(initial.x(1, i) - solver->state().x(1, i), expected, 1e-9 * expected);
    EXPECT_NEAR(solver->state().v(1, i), -kGravity * h * n, 1e-9 * kGravity * h * n);
  }
}

// V2: MuJoCo integrates our springs, so the chain rests at Hooke's statics.
TEST(MujocoSolver, HangingChainMatchesHookesLaw) {
  const GridClothSpec spec = fixtures::hanging_chain(0.05);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  auto solver =
      mujoco_cloth(model, initial_grid_state(*model, spec, 0.0, 0), {}, with_step(1e-3, 3.0));
  run(*solver, 20.0, 1e-3);
  const auto& x = solver->state().x;
  double extension = 0.0;
  for (int j = 0; j < 10; ++j) extension += (x.col(j + 1) - x.col(j)).norm() - 0.05;
  EXPECT_NEAR(extension, 0.053955, 1e-3 * 0.053955);
  // The pinned top particle is where it was built.
  EXPECT_EQ(x.col(10), initial_grid_state(*model, spec, 0.0, 0).x.col(10));
  std::printf("mujoco chain: %.6f of Hooke's law\n", extension / 0.053955);
}

// Each particle of a sheet at rest on the floor sinks its own weight over k into its geom's
// radius (the springs are at rest), and the floor carries the sheet's weight, downwards.
TEST(MujocoSolver, SheetRestsItsWeightOverStiffnessDeepAndLoadsTheFloor) {
  const Rig setup;
  GridClothSpec spec = fixtures::bullet_test_sheet(5, 0.2, {0, setup.radius, 0}, 0.05);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  auto solver = mujoco_cloth(model, initial_grid_state(*model, spec, 0.0, 0),
                             {fixtures::floor_collider()}, setup);
  run(*solver, 1.5, setup.dt);
  double weight = 0.0;
  for (int i = 0; i < model->particle_count(); ++i) {
    const double sag = model->mass[i] * kGravity / setup.contact.stiffness;  // m
    EXPECT_NEAR(solver->state().x(1, i), setup.radius - sag, 0.01 * sag) << "particle " << i;
    weight += model->mass[i] * kGravity;
  }
  const ColliderForce floor = solver->collider_forces().at(0);
  EXPECT_NEAR(floor.normal, weight, 0.01 * weight);
  EXPECT_LT(floor.friction, 1e-3 * weight);
  EXPECT_TRUE(floor.force.isApprox(Eigen::Vector3d(0.0, -weight, 0.0), 0.01))
      << floor.force.transpose();
}

// Two particles meeting head on without gravity, 0.2 m/s apart: their self-contact spheres
// (radius half the thickness) touch at the thickness and press in by the speed times
// sqrt(m_pair / k) at most (less with the damping), momentum is kept exactly, and they part.
TEST(MujocoSolver, SelfContactMeetsAtTheThicknessWithThePairStiffness) {
  Rig setup;
  setup.self_collision.enabled = true;
  setup.self_collision.thickness = 0.01;  // m
  setup.self_collision.stiffness = 200.0;
  setup.self_collision.damping = 0.0;
  const GridClothSpec spec = fixtures::beads(2, 0.002, false);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  ClothState initial = initial_grid_state(*model, spec, 0.0, 0);
  initial.x.col(0) = Eigen::Vector3d(0.0, 1.0, 0.0);
  initial.x.col(1) = Eigen::Vector3d(0.03, 1.0, 0.0);
  initial.v.col(0) = Eigen::Vector3d(0.1, 0.0, 0.0);
  initial.v.col(1) = Eigen::Vector3d(-0.1, 0.0, 0.0);
  mujoco::MujocoOptions options;
  options.gravity = Eigen::Vector3d::Zero();
  options.dt = 1e-4;
  options.particle_radius = setup.radius;
  options.self_collision = setup.self_collision;
  auto solver = mujoco::make_mujoco_solver("mujoco", model, initial, {}, options);
  double closest = 1.0;  // m
  for (int k = 0; k < 3000; ++k) {
    solver->step(options.dt);
    const ClothState& s = solver->state();
    closest = std::min(closest, (s.x.col(1) - s.x.col(0)).norm());
    EXPECT_NEAR((s.v.col(0) + s.v.col(1)).norm(), 0.0, 1e-12);  // equal masses
  }
  const double pressed = 0.2 * std::sqrt(0.001 / 200.0);  // m: v sqrt(m_pair / k)
  EXPECT_NEAR(closest, 0.01 - pressed, 0.02 * pressed);
  const ClothState& end = solver->state();
  EXPECT_NEAR(end.v(0, 1) - end.v(0, 0), 0.2, 0.01);  // parted at the speed they met, undamped
  std::printf("mujoco self-contact: closest %.6f m (thickness less %.6f m)\n", closest, pressed);
}

// A particle on a plane tilted by `degrees` about z, with friction 0.3 (16.7 degrees): its
// displacement along the slope and its speed after one second.
std::pair<double, double> slide(double degrees, const mujoco::MujocoSettings& numerics) {
  Rig setup;
  setup.numerics = numerics;
  const double theta = degrees * std::numbers::pi / 180.0;
  Collider incline = fixtures::floor_collider();
  incline.name = "incline";
  incline.rotation = {0.0, 0.0, degrees};
  incline.friction = incline.static_friction = 0.3;
  const Eigen::Vector3d normal(-std::sin(theta), std::cos(theta), 0.0);
  const Eigen::Vector3d down_slope(-std::cos(theta), -std::sin(theta), 0.0);
  const GridClothSpec spec = fixtures::beads(2, 0.005, false);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  ClothState initial = initial_grid_state(*model, spec, 0.0, 0);
  // Resting on the plane: its radius less its weight's normal part over k off it.
  const double depth = 0.005 * kGravity * std::cos(theta) / setup.contact.stiffness;
  initial.x.col(0) = (setup.radius - depth) * normal;
  initial.x.col(1) = initial.x.col(0) + Eigen::Vector3d(0.0, 0.0, 0.1);
  auto solver = mujoco_cloth(model, initial, {incline}, setup);
  run(*solver, 1.0, setup.dt);
  const ClothState& end = solver->state();
  return {(end.x.col(0) - initial.x.col(0)).dot(down_slope), end.v.col(0).dot(down_slope)};
}

TEST(MujocoSolver, ParticleHoldsBelowTheFrictionAngleAndSlidesAboveIt) {
  // Below it: the friction row takes out one step's sliding per step, so the particle creeps at
  // dt g sin(theta) (2 mm/s at 1 ms), a tenth of the viscous creep below.
  const auto [held, held_speed] = slide(12.0, mujoco::MujocoSettings{});
  const double step_creep = 1e-3 * kGravity * std::sin(12.0 * std::numbers::pi / 180.0);  // m/s
  EXPECT_NEAR(held_speed, step_creep, 0.1 * step_creep);
  EXPECT_LT(held, 1.1 * step_creep);  // m over the second
  const double theta = 22.0 * std::numbers::pi / 180.0;
  const double a = kGravity * (std::sin(theta) - 0.3 * std::cos(theta));  // m/s^2
  const auto [slid, speed] = slide(22.0, mujoco::MujocoSettings{});
  EXPECT_NEAR(speed, a * 1.0, 0.02 * a);
  EXPECT_NEAR(slid, 0.5 * a, 0.03 * 0.5 * a);
  // With equal impedances (impratio 1) friction is the contact's viscous damper alone, and the
  // particle creeps at m g sin(theta) / c below the friction angle.
  mujoco::MujocoSettings viscous;
  viscous.impratio = 1.0;
  const auto [crept, creep_speed] = slide(12.0, viscous);
  const double creep = 0.005 * kGravity * std::sin(12.0 * std::numbers::pi / 180.0) / 0.5;
  EXPECT_NEAR(creep_speed, creep, 0.1 * creep);
  EXPECT_GT(crept, 0.5 * creep);
  std::printf("mujoco incline: held %.2e m, slid %.4f m at %.4f m/s (a t = %.4f), crept %.4f m\n",
              held, slid, speed, a, crept);
}

// Kinematic colliders are heavy free bodies whose velocity MuJoCo's contacts see: a box sliding
// under a sheet carries it by friction (a mocap body would slide out from under it).
TEST(MujocoSolver, MovingBoxCarriesTheClothByFriction) {
  const Rig setup;
  Collider box;
  box.name = "box";
  box.shape = ColliderShape::box;
  box.center = {0.0, -0.05, 0.0};
  box.half_extents = {0.5, 0.05, 0.5};
  box.friction = box.static_friction = 0.5;
  box.motion.velocity = {0.2, 0.0, 0.0};
  GridClothSpec spec = fixtures::bullet_test_sheet(5, 0.2, {0, setup.radius, 0}, 0.05);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  const ClothState initial = initial_grid_state(*model, spec, 0.0, 0);
  auto solver = mujoco_cloth(model, initial, {box}, setup);
  run(*solver, 1.0, setup.dt);
  const double moved = (solver->state().x.row(0).mean() - initial.x.row(0).mean());
  // It catches up at mu g = 4.9 m/s^2 within 0.04 s, slipping 4 mm.
  EXPECT_NEAR(moved, 0.2 - 0.2 * 0.2 / (2.0 * 0.5 * kGravity), 0.005);
  EXPECT_NEAR(solver->state().v.row(0).mean(), 0.2, 0.005);
  EXPECT_GT(solver->state().x.row(1).minCoeff(), 0.0);  // on the box, which moves sideways only
}

TEST(MujocoSolver, PinsHoldAndAttachedPinsFollowTheirCollider) {
  GridClothSpec spec = fixtures::hanging_sheet(7, 0.05, fixtures::kSoftSprings);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  const ClothState initial = initial_grid_state(*model, spec, 0.0, 0);
  std::vector<int> pinned;
  for (int i = 0; i < model->particle_count(); ++i)
    if (model->is_pinned(i)) pinned.push_back(i);
  ASSERT_EQ(pinned.size(), 2u);
  {
    auto solver = mujoco_cloth(model, initial, {}, with_step(5e-4, 1.0));
    run(*solver, 0.5, 5e-4);
    for (const int i : pinned) EXPECT_EQ(solver->state().x.col(i), initial.x.col(i));
    EXPECT_LT(solver->state().x.row(1).minCoeff(), initial.x.row(1).minCoeff() - 1e-4);  // sags
  }
  // The same pins carried by a bar moving at 0.1 m/s (far above the cloth: no contact).
  Collider bar = fixtures::ball_collider({0.0, 3.0, 0.0}, 0.01);
  bar.name = "bar";
  bar.motion.velocity = {0.1, 0.0, 0.0};
  Rig setup = with_step(5e-4, 1.0);
  setup.attachments = std::make_shared<const Attachments>(
      make_attachments({bar}, {{pinned[0], 0}, {pinned[1], 0}}, initial.x, 0.0));
  auto solver = mujoco_cloth(model, initial, {bar}, setup);
  run(*solver, 0.5, 5e-4);
  for (const int i : pinned) {
    EXPECT_TRUE(
        solver->state().x.col(i).isApprox(initial.x.col(i) + Eigen::Vector3d(0.05, 0, 0), 1e-12));
    EXPECT_TRUE(solver->state().v.col(i).isApprox(Eigen::Vector3d(0.1, 0, 0), 1e-12));
  }
}

// What the mapping does not carry is refused before any model is built.
TEST(MujocoSolver, MeshAndDynamicCollidersAreRefused) {
  GridClothSpec spec = fixtures::bullet_test_sheet(5, 0.2, {0, 0.5, 0}, 0.05);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  const ClothState initial = initial_grid_state(*model, spec, 0.0, 0);
  Collider ball = fixtures::ball_collider({0.0, 0.7, 0.0}, 0.05);
  ball.dynamic_mass = 0.1;  // kg
  EXPECT_THROW(mujoco_cloth(model, initial, {ball}), std::invalid_argument);
  Collider mesh = fixtures::ball_collider();
  mesh.shape = ColliderShape::mesh;
  EXPECT_THROW(mujoco_cloth(model, initial, {mesh}), std::invalid_argument);
}

TEST(MujocoSolver, FullContactBufferStopsWithAnError) {
  Rig setup;
  setup.numerics.max_contacts = 3;
  GridClothSpec spec = fixtures::bullet_test_sheet(5, 0.2, {0, 0.02, 0}, 0.05);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  const ClothState initial = initial_grid_state(*model, spec, 0.0, 0);
  auto solver = mujoco_cloth(model, initial, {fixtures::floor_collider()}, setup);
  ClothState last = initial;
  for (int k = 0; k < 2000 && solver->status() == SolverStatus::ok; ++k) {
    last = solver->state();
    solver->step(setup.dt);
  }
  EXPECT_EQ(solver->status(), SolverStatus::error);
  EXPECT_NE(solver->message().find("max_contacts above 3"), std::string::npos) << solver->message();
  // The state stays the last full step's.
  EXPECT_EQ(solver->state().x, last.x);
}

}  // namespace
}  // namespace drapelab
