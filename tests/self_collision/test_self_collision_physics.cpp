// Self-collision with known answers, on small cloths stepped in-process: stacked layers rest one
// thickness apart and never cross, layers stick below the friction angle and slide at
// g (sin - mu cos) above it, and a sheet thrown faster than a thickness per step does not pass
// through another (the step is split).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "drapelab/contact_model.hpp"
#include "drapelab/self_intersections.hpp"
#include "drapelab/spring_damper_solver.hpp"
#include "fixtures/colliders.hpp"
#include "fixtures/sheets.hpp"
#include "layered_cloth.hpp"
#include "self_collision/self_contact.hpp"

namespace drapelab {
namespace {

constexpr double kThickness = 0.004;  // m, between layers and from the floor

SelfCollisionSettings layers(double stiffness, double friction) {
  SelfCollisionSettings s;
  s.enabled = true;
  s.thickness = kThickness;
  s.stiffness = stiffness;
  s.damping = 0.02;
  s.friction = friction;
  s.static_friction = friction;
  return s;
}

// Two 11 x 11 sheets, 0.36 m square, one 2.4 cm above the other, dropped on a floor.
TEST(SelfCollisionPhysics, StackedSheetsRestOneThicknessApartAndNeverCross) {
  const int n = 11;
  GridClothSpec bottom = fixtures::flat_sheet(n, 0.36, {0, 0.006, 0}, 0.03);
  GridClothSpec top = fixtures::flat_sheet(n, 0.36, {0, 0.030, 0}, 0.03);
  bottom.thickness = top.thickness = kThickness;
  auto model = std::make_shared<const ClothModel>(fixtures::stacked_cloth({bottom, top}));
  const double k = 500.0;  // N/m
  SpringDamperSettings settings;
  settings.air_damping = 3.0;
  settings.self_collision = layers(k, 0.3);
  settings.self_collision.damping = 0.2;  // about a third of critical for one particle
  settings.contacts =
      std::make_shared<const ContactModel>(std::vector<Collider>{fixtures::floor_collider()},
                                           ContactParameters{5000.0, 0.5}, kThickness);
  ClothState start{model->rest_positions, Eigen::Matrix3Xd::Zero(3, model->particle_count())};
  SpringDamperSolver solver("ours", model, start, settings);
  const SelfIntersectionCounter audit(model->triangles);
  int frames = 0;
  fixtures::run_frames(solver, 1.2, 2e-4, 1.0 / 30.0, [&](const ClothState& state) {
    EXPECT_EQ(audit.count(state.x), 0) << "at t = " << state.time << " s";
    ++frames;
  });
  ASSERT_EQ(solver.status(), SolverStatus::ok) << solver.message();
  EXPECT_EQ(frames, 37);
  // At rest each top particle's weight m g rests on at least one contact of stiffness k below it,
  // so the layers sag into each other by at most m g / k (3.5 um here); 0.1 mm covers what is
  // left of the motion after 1.2 s.
  const int per_sheet = n * n;
  const double weight = model->mass[per_sheet] * 9.81;  // N, one top particle
  const Eigen::Matrix3Xd& x = solver.state().x;
  double lowest = 1.0, highest = 0.0;
  for (int i = 0; i < per_sheet; ++i) {
    const double gap = x(1, per_sheet + i) - x(1, i);  // m, top over the bottom particle below
    lowest = std::min(lowest, gap);
    highest = std::max(highest, gap);
  }
  EXPECT_GE(lowest, kThickness - weight / k - 1e-4);
  EXPECT_LE(highest, kThickness + 1e-4) << "lowest " << lowest;
  EXPECT_GT(solver.self_contact_stats()->contacts_last, per_sheet / 2);
}

// A 5 x 5 sheet resting on a pinned sheet tilted by `degrees` about z; returns the small sheet's
// mean velocity along the slope (m/s, positive downhill) at 0.2 s and at 0.4 s.
std::pair<double, double> slide(double degrees, double friction) {
  const Eigen::Matrix3d tilt = euler_rotation({0.0, 0.0, degrees});
  const Eigen::Vector3d normal = tilt * Eigen::Vector3d::UnitY();
  GridClothSpec ground = fixtures::flat_sheet(15, 1.0, {0, 0.5, 0}, 0.2);
  ground.rotation = {0.0, 0.0, degrees};
  ground.pins = {PinWithin{{0, 0.5, 0}, 2.0}};
  GridClothSpec block = fixtures::soft_sheet(
      5, 0.08, Eigen::Vector3d(0, 0.5, 0) + (kThickness - 2e-6) * normal, 0.004);
  block.rotation = ground.rotation;
  ground.thickness = block.thickness = kThickness;
  auto model = std::make_shared<const ClothModel>(fixtures::stacked_cloth({ground, block}));
  SpringDamperSettings settings;
  settings.self_collision = layers(200.0, friction);
  settings.self_collision.damping = 0.05;  // N*s/m: a seventh of critical for one particle
  ClothState start{model->rest_positions, Eigen::Matrix3Xd::Zero(3, model->particle_count())};
  SpringDamperSolver solver("ours", model, start, settings);
  const Eigen::Vector3d downhill =
      (Eigen::Vector3d(0, -9.81, 0) - normal * normal.dot(Eigen::Vector3d(0, -9.81, 0)))
          .normalized();
  const int first = 15 * 15;
  std::vector<double> speeds;
  fixtures::run_frames(solver, 0.4, 1e-4, 0.2, [&](const ClothState& state) {
    speeds.push_back(state.v.rightCols(state.v.cols() - first).rowwise().mean().dot(downhill));
  });
  EXPECT_EQ(solver.status(), SolverStatus::ok) << solver.message();
  EXPECT_GT(solver.self_contact_stats()->contacts_last, 0);
  return {speeds.at(1), speeds.at(2)};
}

TEST(SelfCollisionPhysics, LayersStickBelowTheFrictionAngle) {
  // tan 15 deg = 0.27 < 0.5.
  const auto [early, late] = slide(15.0, 0.5);
  EXPECT_LT(std::abs(late), 2e-3);
  EXPECT_LT(std::abs(early), 2e-3);
}

TEST(SelfCollisionPhysics, LayersSlideAtGravityLessFrictionAboveIt) {
  const double degrees = 40.0, mu = 0.3;
  const double theta = degrees * std::numbers::pi / 180.0;
  const double expected = 9.81 * (std::sin(theta) - mu * std::cos(theta));  // m/s^2, 4.05
  const auto [early, late] = slide(degrees, mu);
  const double measured = (late - early) / 0.2;
  EXPECT_NEAR(measured, expected, 0.05 * expected);
}

// A 5 x 5 sheet thrown at 20 m/s onto a pinned sheet with steps of 1 ms: 20 mm per step, five
// thicknesses. The steps are split so that no particle moves more than a quarter thickness
// relative to the cloth's mean motion, and it stops on the sheet.
TEST(SelfCollisionPhysics, AFastSheetDoesNotTunnelThroughAnother) {
  GridClothSpec target = fixtures::flat_sheet(15, 0.4, {0, 0.5, 0}, 0.05);
  target.pins = {PinWithin{{0, 0.5, 0}, 1.0}};
  GridClothSpec thrown = fixtures::flat_sheet(5, 0.1, {0.01, 0.56, 0.013}, 0.01);
  target.thickness = thrown.thickness = kThickness;
  auto model = std::make_shared<const ClothModel>(fixtures::stacked_cloth({target, thrown}));
  SpringDamperSettings settings;
  settings.integrator = Integrator::implicit_euler;
  settings.self_collision = layers(5e4, 0.3);
  settings.self_collision.damping = 0.05;
  ClothState start{model->rest_positions, Eigen::Matrix3Xd::Zero(3, model->particle_count())};
  start.v.rightCols(25).row(1).setConstant(-20.0);
  SpringDamperSolver solver("ours", model, start, settings);
  const SelfIntersectionCounter audit(model->triangles);
  fixtures::run_frames(solver, 0.05, 1e-3, 1e-3, [&](const ClothState& state) {
    EXPECT_EQ(audit.count(state.x), 0) << "at t = " << state.time << " s";
  });
  ASSERT_EQ(solver.status(), SolverStatus::ok) << solver.message();
  EXPECT_GT(solver.stats().split_steps, 0);
  EXPECT_GE(solver.stats().split_pieces_max, 20);
  EXPECT_EQ(solver.stats().unresolved_fast_steps, 0);
  EXPECT_GT(solver.state().x.rightCols(25).row(1).minCoeff(), 0.5);
}

}  // namespace
}  // namespace drapelab
