// Distance constraints (drapelab/distance_constraints.hpp) in our solver under every integrator: a
// hard chain holds its lengths while it swings, a hard pendulum keeps its period, a rope is never
// longer than its length and changes nothing while slack, a soft constraint sags as Hooke says.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "drapelab/distance_constraints.hpp"
#include "drapelab/grid_cloth.hpp"
#include "drapelab/integrators.hpp"
#include "drapelab/spring_damper_solver.hpp"
#include "fixtures/chains.hpp"
#include "fixtures/constraint_ends.hpp"

namespace drapelab {
namespace {

constexpr double kG = 9.81;  // m/s^2

std::shared_ptr<const ClothModel> free_particles(int count, double particle_mass,
                                                 bool pin_first = false) {
  return std::make_shared<const ClothModel>(
      build_grid_cloth(fixtures::beads(count, particle_mass, pin_first)));
}

ClothState state_at(const Eigen::Matrix3Xd& x) {
  ClothState s;
  s.x = x;
  s.v = Eigen::Matrix3Xd::Zero(3, x.cols());
  return s;
}

DistanceConstraint hard(int a, ConstraintEnd b, double length) {
  DistanceConstraint c;
  c.a = a;
  c.b = b;
  c.length = length;
  c.mode = ConstraintMode::hard;
  return c;
}

using fixtures::particle_end;
using fixtures::point_end;

SpringDamperSettings settings_for(Integrator integrator,
                                  std::shared_ptr<const DistanceConstraints> constraints) {
  SpringDamperSettings settings;
  settings.integrator = integrator;
  settings.gravity = {0.0, -kG, 0.0};
  settings.constraints = std::move(constraints);
  settings.vbd.iterations = 20;
  return settings;
}

// The energy of free particles under gravity (J).
double energy(const ClothModel& model, const ClothState& s) {
  double e = 0.0;
  for (int i = 0; i < model.particle_count(); ++i)
    e += model.mass[i] * (0.5 * s.v.col(i).squaredNorm() + kG * s.x(1, i));
  return e;
}

// A chain of five 20 g particles on 10 cm hard links, the first hung from a fixed point, released
// horizontal: it swings down and whips. Every length stays within its tolerance after every step.
TEST(HardConstraints, SwingingChainHoldsItsLengthsUnderEveryIntegrator) {
  const int n = 5;
  const double link = 0.1;  // m
  const Eigen::Vector3d top(0.0, 1.0, 0.0);
  auto model = free_particles(n, 0.02);
  Eigen::Matrix3Xd x(3, n);
  for (int i = 0; i < n; ++i) x.col(i) = top + Eigen::Vector3d(link * (i + 1), 0.0, 0.0);
  auto constraints = std::make_shared<DistanceConstraints>();
  constraints->list.push_back(hard(0, point_end(top), link));
  for (int i = 1; i < n; ++i) constraints->list.push_back(hard(i, particle_end(i - 1), link));
  for (Integrator integrator : all_integrators()) {
    SCOPED_TRACE(integrator_name(integrator));
    SpringDamperSolver solver("chain", model, state_at(x), settings_for(integrator, constraints));
    const double e0 = energy(*model, solver.state());
    const double h = 5e-4;  // s
    double worst = 0.0, lowest = 1.0;
    for (int k = 0; k < 2000; ++k) {  // 1 s: down, through the bottom and up the other side
      solver.step(h);
      ASSERT_EQ(solver.status(), SolverStatus::ok) << solver.message();
      worst = std::max(worst, constraints->largest_error(solver.state().time, solver.state().x));
      lowest = std::min(lowest, solver.state().x.row(1).minCoeff());
    }
    EXPECT_LE(worst, 1e-6);        // the tolerance
    EXPECT_LT(lowest, 1.0 - 0.4);  // m: the chain swung through the bottom
    // The projection takes energy out (its velocity step is inelastic) and never puts it in.
    const double e1 = energy(*model, solver.state());
    EXPECT_LT(e1, e0 + 1e-3 * std::abs(e0)) << "energy " << e0 << " -> " << e1;
    RecordProperty(std::string("energy_change_") + integrator_name(integrator),
                   std::to_string(e1 - e0));
  }
}

// A 0.5 m pendulum on one hard constraint, 5 degrees out: its period is 2 pi sqrt(L/g) (1 +
// theta^2/16) within 0.2 % for every integrator.
TEST(HardConstraints, PendulumKeepsItsPeriod) {
  const double length = 0.5, angle = 5.0 * std::numbers::pi / 180.0;
  const Eigen::Vector3d top(0.0, 1.0, 0.0);
  auto model = free_particles(2, 0.1, /*pin_first=*/true);  // particle 0 stays aside, pinned
  Eigen::Matrix3Xd x(3, 2);
  x.col(0) = Eigen::Vector3d(5.0, 0.0, 0.0);
  x.col(1) = top + length * Eigen::Vector3d(std::sin(angle), -std::cos(angle), 0.0);
  auto constraints = std::make_shared<DistanceConstraints>();
  constraints->list.push_back(hard(1, point_end(top), length));
  const double expected =
      2.0 * std::numbers::pi * std::sqrt(length / kG) * (1.0 + angle * angle / 16.0);
  for (Integrator integrator : all_integrators()) {
    SCOPED_TRACE(integrator_name(integrator));
    SpringDamperSolver solver("pendulum", model, state_at(x),
                              settings_for(integrator, constraints));
    const double h = 1e-3;          // s
    std::vector<double> crossings;  // s: where x goes from + to -, interpolated
    double previous = solver.state().x(0, 1);
    while (solver.state().time < 3.5 * expected) {
      solver.step(h);
      const double now = solver.state().x(0, 1);
      if (previous > 0.0 && now <= 0.0)
        crossings.push_back(solver.state().time - h * now / (now - previous));
      previous = now;
    }
    ASSERT_GE(crossings.size(), 3u);
    const double period =
        (crossings.back() - crossings.front()) / (static_cast<double>(crossings.size()) - 1.0);
    EXPECT_NEAR(period / expected, 1.0, 2e-3) << "period " << period << " s, expected " << expected;
  }
}

// A particle 0.3 m below a point on a 0.5 m rope, thrown sideways: while slack it moves exactly as
// without the rope; the rope then catches it and is never longer than its length.
TEST(RopeConstraints, SlackChangesNothingAndTautNeverLonger) {
  const double length = 0.5;  // m
  const Eigen::Vector3d top(0.0, 1.0, 0.0);
  auto model = free_particles(2, 0.05, /*pin_first=*/true);  // particle 0 stays aside, pinned
  Eigen::Matrix3Xd x(3, 2);
  x.col(0) = Eigen::Vector3d(5.0, 0.0, 0.0);
  x.col(1) = top + Eigen::Vector3d(0.0, -0.3, 0.0);
  ClothState start = state_at(x);
  start.v.col(1) = Eigen::Vector3d(1.0, 0.0, 0.5);  // m/s
  auto rope = std::make_shared<DistanceConstraints>();
  rope->list.push_back(hard(1, point_end(top), length));
  rope->list.back().mode = ConstraintMode::rope;
  for (Integrator integrator : all_integrators()) {
    SCOPED_TRACE(integrator_name(integrator));
    SpringDamperSolver tied("tied", model, start, settings_for(integrator, rope));
    SpringDamperSolver free("free", model, start, settings_for(integrator, nullptr));
    const double h = 1e-3;
    bool slack = true;
    int slack_steps = 0;
    double longest = 0.0;
    for (int k = 0; k < 1500; ++k) {
      tied.step(h);
      free.step(h);
      const double l = (tied.state().x.col(1) - top).norm();
      longest = std::max(longest, l);
      slack = slack && (free.state().x.col(1) - top).norm() < length;
      if (slack) {  // the same bits as the untied particle
        ++slack_steps;
        ASSERT_EQ(tied.state().x.col(1), free.state().x.col(1)) << "step " << k;
        ASSERT_EQ(tied.state().v.col(1), free.state().v.col(1)) << "step " << k;
      }
    }
    EXPECT_GT(slack_steps, 100);                // it flew free for a while ...
    EXPECT_GT(longest, length * (1.0 - 1e-6));  // ... then the rope caught it ...
    EXPECT_LE(longest, length * (1.0 + 1e-6));  // ... never longer than its length
    EXPECT_LE(rope->largest_error(tied.state().time, tied.state().x), 1e-6);
  }
}

// A 50 g particle on a soft constraint of 20 N/m, hanging from a fixed point (and, second case,
// from a pinned particle): it settles where the spring holds its weight, extension m g / k.
TEST(SoftConstraints, StaticSagIsHookes) {
  const double mass = 0.05, k = 20.0, c = 0.5, length = 0.3;  // kg, N/m, N*s/m, m
  const double sag = mass * kG / k;                           // m
  for (bool to_particle : {false, true}) {
    // Particle 0 is the pinned top (only used in the second case), particle 1 hangs.
    auto model = free_particles(2, mass, /*pin_first=*/true);
    Eigen::Matrix3Xd x(3, 2);
    x.col(0) = Eigen::Vector3d(0.0, 1.0, 0.0);
    x.col(1) = Eigen::Vector3d(0.0, 1.0 - length, 0.0);  // starts at the rest length: it bobs
    auto constraints = std::make_shared<DistanceConstraints>();
    DistanceConstraint spring;
    spring.a = 1;
    spring.b = to_particle ? particle_end(0) : point_end(x.col(0));
    spring.length = length;
    spring.mode = ConstraintMode::soft;
    spring.stiffness = k;
    spring.damping = c;
    constraints->list.push_back(spring);
    for (Integrator integrator : all_integrators()) {
      SCOPED_TRACE(std::string(integrator_name(integrator)) +
                   (to_particle ? ", to a particle" : ""));
      SpringDamperSolver solver("soft", model, state_at(x), settings_for(integrator, constraints));
      for (int step = 0; step < 3000; ++step) solver.step(1e-3);  // 3 s: the bob decays as e^-5t
      ASSERT_EQ(solver.status(), SolverStatus::ok) << solver.message();
      const double extension = 1.0 - solver.state().x(1, 1) - length;
      EXPECT_NEAR(extension / sag, 1.0, 1e-4) << "extension " << extension << " m";
      EXPECT_NEAR(solver.state().x(0, 1), 0.0, 1e-12);
    }
  }
}

// A stiff soft constraint (a 200 Hz spring) at a step 20 times past its explicit limit: implicit
// Euler and vbd take it in their solves (as a coupling) and stay stable.
TEST(SoftConstraints, StiffSpringIsImplicitInTheImplicitSchemes) {
  const double mass = 0.01, k = mass * std::pow(2.0 * std::numbers::pi * 200.0, 2);  // N/m
  auto model = free_particles(2, mass, /*pin_first=*/true);
  Eigen::Matrix3Xd x(3, 2);
  x.col(0) = Eigen::Vector3d(0.0, 1.0, 0.0);
  x.col(1) = Eigen::Vector3d(0.0, 0.8, 0.0);
  auto constraints = std::make_shared<DistanceConstraints>();
  DistanceConstraint spring;
  spring.a = 1;
  spring.b = particle_end(0);
  spring.length = 0.2;
  spring.mode = ConstraintMode::soft;
  spring.stiffness = k;
  constraints->list.push_back(spring);
  const double h = 20.0 * 2.0 / std::sqrt(k / mass);  // s: twenty explicit stability limits
  for (Integrator integrator : {Integrator::implicit_euler, Integrator::vbd}) {
    SCOPED_TRACE(integrator_name(integrator));
    SpringDamperSolver solver("stiff", model, state_at(x), settings_for(integrator, constraints));
    for (int step = 0; step < 500; ++step) solver.step(h);
    ASSERT_EQ(solver.status(), SolverStatus::ok) << solver.message();
    EXPECT_NEAR(1.0 - solver.state().x(1, 1) - 0.2, mass * kG / k, 0.05 * mass * kG / k);
  }
}

}  // namespace
}  // namespace drapelab
