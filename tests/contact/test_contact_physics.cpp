// Collision response with known answers (docs/validation.md, "V8 Cloth on a sphere" and "V9
// Friction on an incline") and the penalty model's bounds: weight balance, depth against stiffness,
// a cloth at rest on a cylinder's cap, and a moving collider pushing through a pinned cloth.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "drapelab/collision_metrics.hpp"
#include "drapelab/contact_model.hpp"
#include "drapelab/grid_cloth.hpp"
#include "drapelab/spring_damper_solver.hpp"
#include "drapelab/stability.hpp"
#include "fixtures/colliders.hpp"
#include "fixtures/sheets.hpp"

namespace drapelab {
namespace {

constexpr double kGravity = 9.81;  // m/s^2

struct Simulation {
  std::shared_ptr<const ClothModel> model;
  std::shared_ptr<const ContactModel> contacts;
  std::unique_ptr<SpringDamperSolver> solver;
  double h = 0.0;  // s

  void run_for(double seconds) {
    const int steps = static_cast<int>(std::lround(seconds / h));
    for (int k = 0; k < steps && solver->status() == SolverStatus::ok; ++k) solver->step(h);
    ASSERT_EQ(solver->status(), SolverStatus::ok) << solver->message();
  }
  CollisionMetrics collisions() const {
    return compute_collision_metrics(*model, solver->state(), *contacts, solver->state().time);
  }
};

// A solver at 0.8 x its integrator's stable step estimate for the cloth with its contacts (implicit
// Euler and vbd, which have no stable step: 1/240 s, implicit Euler's default in the loader;
// adaptive substeps: steps of 1/120 s, the loader's default, each split by the solver).
Simulation make_simulation(const GridClothSpec& spec, std::vector<Collider> colliders,
                           ContactParameters contact, double air_damping,
                           const ClothState* initial = nullptr,
                           Integrator integrator = Integrator::symplectic_euler,
                           bool adaptive = false) {
  Simulation s;
  s.model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  s.contacts = std::make_shared<const ContactModel>(std::move(colliders), contact, spec.thickness);
  SpringDamperSettings settings;
  settings.air_damping = air_damping;
  settings.contacts = s.contacts;
  settings.integrator = integrator;
  settings.adaptive_substeps = adaptive;
  s.h = integrator == Integrator::implicit_euler || integrator == Integrator::vbd
            ? 1.0 / 240.0
            : 0.8 * stable_step_estimate(*s.model, air_damping,
                                         {contact.stiffness, contact.damping}, integrator);
  if (adaptive) s.h = 1.0 / 120.0;
  const ClothState start = initial ? *initial : initial_grid_state(*s.model, spec, 0.0, 0);
  s.solver = std::make_unique<SpringDamperSolver>("test", s.model, start, settings);
  return s;
}

double total_normal_force(const SpringDamperSolver& solver) {
  double sum = 0.0;
  for (const auto& total : solver.contact_totals()) sum += total.normal_force;
  return sum;
}

// Flat cloth settled on the floor: every particle carries its own weight, so each sinks m g / k and
// the normal forces add up to M g.
TEST(ContactPhysics, RestingClothNormalForcesBalanceItsWeightAndSagIsMgOverK) {
  for (double stiffness : {100.0, 1000.0}) {
    // Particles resting at clearance 0.
    const GridClothSpec spec = fixtures::soft_sheet(11, 0.5, {0, 0.005, 0}, 0.1);
    const double particle_mass = 0.1 / 121;                       // kg
    const double damping = std::sqrt(stiffness * particle_mass);  // N*s/m: damping ratio 1/2
    Simulation s = make_simulation(spec, {fixtures::floor_collider()}, {stiffness, damping}, 2.0);
    s.run_for(2.0);
    const double weight = 0.1 * kGravity;  // N
    EXPECT_NEAR(total_normal_force(*s.solver), weight, 0.01 * weight) << stiffness;
    const double sag = (0.1 / 121) * kGravity / stiffness;  // m, per particle
    const CollisionMetrics c = s.collisions();
    EXPECT_NEAR(c.max_penetration, sag, 0.05 * sag) << stiffness;
    EXPECT_EQ(c.contact_count, 121);
  }
}

// V8: a 1 m, 41 x 41 cloth dropped 0.2 m onto a sphere of radius 0.3 m; with fixed steps and with
// adaptive substeps (the same criteria: the longer substeps must not cost the drape its accuracy).
void check_v8_sphere_drape(bool adaptive) {
  SCOPED_TRACE(adaptive ? "adaptive substeps" : "fixed steps");
  const double radius = 0.3, thickness = 0.005, stiffness = 1000.0;
  std::vector<double> penetrations;
  for (double k : {stiffness, 3.0 * stiffness}) {
    const GridClothSpec spec = fixtures::soft_sheet(41, 1.0, {0, 0.5 + radius + 0.2, 0}, 0.25);
    const double damping = std::sqrt(k * 0.25 / 1681);  // N*s/m: contact damping ratio about 1/2
    Simulation s =
        make_simulation(spec, {fixtures::ball_collider({0, 0.5, 0}, radius)}, {k, damping}, 2.0,
                        nullptr, Integrator::symplectic_euler, adaptive);
    s.run_for(4.0);
    const CollisionMetrics c = s.collisions();
    const double mean_sag_bound = 0.25 * kGravity / (c.contact_count * k);  // M g / (N_c k)
    // The worst particle sits where the hanging skirt wraps over the sphere and carries its weight,
    // several times the mean load: measured 7-8x the mean-load sag. It stays far inside the shell.
    EXPECT_GT(c.min_clearance, -10.0 * mean_sag_bound) << k;
    EXPECT_LT(c.max_penetration, 0.1 * thickness) << k;
    penetrations.push_back(c.max_penetration);
    // Particles in contact sit at the sphere's radius plus the thickness, less their sag.
    const auto& x = s.solver->state().x;
    int resting = 0;
    for (int i = 0; i < s.model->particle_count(); ++i) {
      const double distance = (x.col(i) - Eigen::Vector3d(0, 0.5, 0)).norm();
      if (distance <= radius + thickness) {
        EXPECT_GT(distance, radius + thickness - 10.0 * mean_sag_bound);
        ++resting;
      }
    }
    EXPECT_GT(resting, 200);
    // Symmetric about the sphere's vertical axis: the centroid within one edge length of it.
    const Eigen::Vector3d centroid = x * s.model->mass / s.model->total_mass();
    EXPECT_LT(std::hypot(centroid.x(), centroid.z()), 1.0 / 40) << k;
    EXPECT_LT(s.solver->state().v.cwiseAbs().maxCoeff(), 0.05);  // settled
  }
  // Penalty depth shrinks as stiffness grows: 3x the stiffness, about a third of the depth.
  EXPECT_NEAR(penetrations[1] / penetrations[0], 1.0 / 3.0, 0.1);
}

TEST(ContactPhysics, V8ClothDrapedOnASphereRestsAtTheThicknessSymmetrically) {
  check_v8_sphere_drape(false);
}

TEST(ContactPhysics, V8DrapeHoldsWithAdaptiveSubsteps) { check_v8_sphere_drape(true); }

// A cloth dropped on a round table rests on the cap at the cap's height plus the thickness.
TEST(ContactPhysics, ClothRestsFlatOnACylindersCap) {
  Collider table;
  table.name = "table";
  table.shape = ColliderShape::cylinder;
  table.center = {0, 0.4, 0};
  table.radius = 0.4;
  table.height = 0.8;  // top at y = 0.8
  const double stiffness = 1000.0;
  const double damping =
      std::sqrt(stiffness * 0.1 / 625);  // N*s/m: contact damping ratio about 1/2
  Simulation s = make_simulation(fixtures::soft_sheet(25, 0.6, {0, 0.85, 0}, 0.1), {table},
                                 {stiffness, damping}, 1.0);
  s.run_for(2.0);
  const auto& x = s.solver->state().x;
  const double particle_weight = (0.1 / 625) * kGravity;  // N
  int on_cap = 0;
  for (int i = 0; i < s.model->particle_count(); ++i) {
    if (std::hypot(x(0, i), x(2, i)) > 0.25) continue;  // well inside the rim
    EXPECT_NEAR(x(1, i), 0.8 + 0.005, 2.0 * particle_weight / stiffness + 1e-6) << i;
    ++on_cap;
  }
  EXPECT_GT(on_cap, 200);
}

// V9: a small patch on a plane tilted by theta with mu = 0.3 sticks iff tan(theta) <= mu (16.70
// deg), and otherwise slides with a = g (sin(theta) - mu cos(theta)).
struct InclineRun {
  double creep = 0.0;         // m, distance moved along the slope between t = 0.5 s and 2.5 s
  double acceleration = 0.0;  // m/s^2 along the slope, from the velocity at 1 s and 2 s
};

InclineRun slide_on_incline(double degrees, Integrator integrator = Integrator::symplectic_euler) {
  Collider incline = fixtures::floor_collider();  // friction 0.3
  incline.rotation = {0, 0, degrees};  // the floor turned about z: the slope descends towards -x
  GridClothSpec spec = fixtures::soft_sheet(5, 0.1, {0, 0, 0}, 0.01);
  const auto model = build_grid_cloth(spec);
  // Lay the patch on the slope, resting at the thickness.
  const Eigen::Matrix3d turn = euler_rotation({0, 0, degrees});
  ClothState start = initial_grid_state(model, spec, 0.0, 0);
  for (int i = 0; i < model.particle_count(); ++i)
    start.x.col(i) = turn * (model.rest_positions.col(i) + Eigen::Vector3d(0, spec.thickness, 0));
  Simulation s = make_simulation(spec, {incline}, {2000.0, 0.02}, 0.0, &start, integrator);
  const Eigen::Vector3d downhill = turn * Eigen::Vector3d(-1, 0, 0);
  auto position = [&] { return s.solver->state().x.rowwise().mean().dot(downhill); };
  auto velocity = [&] { return s.solver->state().v.rowwise().mean().dot(downhill); };
  InclineRun result;
  s.run_for(0.5);
  const double settled = position();
  s.run_for(0.5);
  const double v1 = velocity();
  s.run_for(1.0);
  const double v2 = velocity();
  s.run_for(0.5);
  result.creep = position() - settled;
  result.acceleration = v2 - v1;  // over 1 s
  return result;
}

// Contacts and friction work with every integrator (explicit Euler and midpoint on the contact's
// damping-limited step).
TEST(ContactPhysics, V9SlidesWithTheCoulombAccelerationOnASteepIncline) {
  const double theta = 20.0 * std::numbers::pi / 180.0;
  const double expected = kGravity * (std::sin(theta) - 0.3 * std::cos(theta));
  EXPECT_NEAR(expected, 0.5897, 1e-4);
  for (Integrator integrator : all_integrators()) {
    const InclineRun run = slide_on_incline(20.0, integrator);
    EXPECT_NEAR(run.acceleration, expected, 0.02 * expected) << integrator_name(integrator);
  }
}

TEST(ContactPhysics, V9StickingThresholdIsTheFrictionAngle) {
  const double threshold = std::atan(0.3) * 180.0 / std::numbers::pi;  // 16.70 deg
  for (Integrator integrator : all_integrators()) {
    SCOPED_TRACE(integrator_name(integrator));
    const InclineRun below = slide_on_incline(threshold - 0.5, integrator);
    EXPECT_LT(std::abs(below.creep), 1e-3);  // sticks: less than 1 mm over 2 s
    const InclineRun above = slide_on_incline(threshold + 0.5, integrator);
    EXPECT_GT(above.creep, 0.05);  // slides: a = 0.08 m/s^2 gives 0.16 m over 2 s
  }
}

// A sphere rising at 0.5 m/s through a cloth pinned at its corners: the contact keeps every
// particle outside the sphere (penetration below half the thickness) while it lifts the cloth.
TEST(ContactPhysics, MovingSphereNeverPushesThroughThePinnedCloth) {
  GridClothSpec spec = fixtures::soft_sheet(21, 1.0, {0, 1.0, 0}, 0.1);
  spec.pins = {PinNamed{"corners"}};
  Collider ball = fixtures::ball_collider({0, 0.6, 0}, 0.15);
  ball.motion.velocity = {0, 0.5, 0};
  Simulation s = make_simulation(spec, {ball}, {2000.0, 0.01}, 0.5);
  double worst = 0.0;
  for (int frame = 0; frame < 60; ++frame) {  // 1.2 s: the ball's top rises from 0.75 m to 1.35 m
    s.run_for(0.02);
    worst = std::max(worst, s.collisions().max_penetration);
  }
  EXPECT_LT(worst, 0.5 * spec.thickness);
  // The ball lifts the cloth's centre with it.
  const int centre = 10 * 21 + 10;
  EXPECT_GT(s.solver->state().x(1, centre), 1.25);
}

}  // namespace
}  // namespace drapelab
