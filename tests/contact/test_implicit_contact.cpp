// The linearly implicit penalty contact of symplectic Euler (penalty_contact.hpp): the normal force
// is the one the step's end state implies, so the contact's stiffness and damping do not bound the
// step. Checked on the formula itself, on a particle's normal motion, and on a whole cloth resting
// on a floor at steps where the explicit penalty force diverges.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include "core/penalty_contact.hpp"
#include "drapelab/collision_metrics.hpp"
#include "drapelab/contact_model.hpp"
#include "drapelab/grid_cloth.hpp"
#include "drapelab/spring_damper_solver.hpp"
#include "drapelab/stability.hpp"
#include "fixtures/colliders.hpp"
#include "fixtures/sheets.hpp"

namespace drapelab {
namespace {

constexpr double kStandardGravity = 9.81;  // m/s^2

TEST(LinearlyImplicitNormalForce, SatisfiesTheEndOfStepEquation) {
  const double k = 1000.0, c = 0.2, m = 1.5e-5, h = 1e-4;  // N/m, N*s/m, kg, s
  for (double depth : {1e-5, 2e-3}) {                      // m
    for (double u : {-2.0, -0.01, 0.0}) {                  // m/s, approaching or still
      for (double other : {-5e-3, 0.0, 1e-3}) {            // N along the normal
        const double fn = linearly_implicit_normal_force(depth, u, other, m, h, k, c);
        ASSERT_GT(fn, 0.0);
        const double u_end = u + h / m * (other + fn);               // m/s, the step's end velocity
        const double implied = k * (depth - h * u_end) - c * u_end;  // N, the spring-damper there
        EXPECT_NEAR(fn, implied, 1e-12 * std::abs(fn) + 1e-15) << depth << " " << u << " " << other;
      }
    }
  }
}

TEST(LinearlyImplicitNormalForce, AtRestItIsThePenaltyForceAndAsTheStepShrinksTooTheExplicitOne) {
  const double k = 1000.0, c = 0.2, m = 1.5e-5;   // N/m, N*s/m, kg
  const double depth = m * kStandardGravity / k;  // m: the sag under the particle's weight
  EXPECT_NEAR(linearly_implicit_normal_force(depth, 0.0, -m * kStandardGravity, m, 1e-3, k, c),
              k * depth, 1e-15);
  const double explicit_force = penalty_normal_force(1e-3, -0.5, k, c);  // N
  const double tiny_step = linearly_implicit_normal_force(1e-3, -0.5, 0.0, m, 1e-12, k, c);
  EXPECT_NEAR(tiny_step, explicit_force, 1e-6 * explicit_force);
  // At a step like the cloth's, it is smaller: the contact cannot push more than the step allows.
  EXPECT_LT(linearly_implicit_normal_force(1e-3, -0.5, 0.0, m, 1e-4, k, c), 0.5 * explicit_force);
}

TEST(LinearlyImplicitNormalForce, OnlyPushes) {
  // Separating faster than the spring can hold: no pull.
  EXPECT_EQ(linearly_implicit_normal_force(1e-4, 5.0, 0.0, 1e-3, 1e-3, 1000.0, 0.2), 0.0);
  // Lifted off by a strong outward force.
  EXPECT_EQ(linearly_implicit_normal_force(1e-4, 0.0, 10.0, 1e-3, 1e-3, 1000.0, 0.2), 0.0);
}

// To 4 ulp: the two sides are compiled separately, and a compiler may fuse a multiply and an add
// (FMA) in one and not the other.
TEST(LinearlyImplicitNormalForces, OneContactIsTheClosedForm) {
  const NormalContact contact{Eigen::Vector3d(0.6, 0.8, 0.0), 2e-3,
                              Eigen::Vector3d(0.1, -0.2, 0.3)};
  const Eigen::Vector3d v(0.3, -1.5, 0.2), other(1e-4, -2e-4, 5e-5);  // m/s, N
  double fn = 0.0;
  linearly_implicit_normal_forces(&contact, 1, v, other, 1.5e-5, 1e-4, 1000.0, 0.2, &fn);
  EXPECT_DOUBLE_EQ(fn, linearly_implicit_normal_force(
                           contact.depth, (v - contact.surface_velocity).dot(contact.normal),
                           other.dot(contact.normal), 1.5e-5, 1e-4, 1000.0, 0.2));
}

// Two or three contacts solved together: every pushing force is the spring-damper at the common end
// velocity, and every contact left out would pull there.
TEST(LinearlyImplicitNormalForces, SeveralContactsAreSolvedTogether) {
  const double k = 1000.0, c = 0.2, m = 1.5e-5, h = 5e-4;  // N/m, N*s/m, kg, s: h c / m = 6.7
  const double resistance = c + h * k;
  const NormalContact floor{Eigen::Vector3d::UnitY(), 1e-3, Eigen::Vector3d::Zero()};
  const NormalContact wall{Eigen::Vector3d::UnitX(), 5e-4, Eigen::Vector3d::Zero()};
  const NormalContact slope{Eigen::Vector3d(-0.6, 0.8, 0.0), 2e-4, Eigen::Vector3d(0.0, 0.1, 0.0)};
  const Eigen::Vector3d gravity(0.0, -m * kStandardGravity, 0.0);  // N
  struct Case {
    std::vector<NormalContact> contacts;
    Eigen::Vector3d velocity;  // m/s
  };
  const std::vector<Case> cases = {
      {{floor, wall}, {-0.5, -1.0, 0.0}},         // driven into both
      {{floor, wall}, {2.0, -1.0, 0.0}},          // leaving the wall fast: only the floor pushes
      {{floor, wall, slope}, {-0.2, -0.3, 0.1}},  // three at once
      {{wall, slope}, {0.1, 0.5, 0.0}},
  };
  int pulling_left_out = 0;
  for (const Case& test : cases) {
    const int count = static_cast<int>(test.contacts.size());
    std::vector<double> fn(test.contacts.size());
    linearly_implicit_normal_forces(test.contacts.data(), count, test.velocity, gravity, m, h, k, c,
                                    fn.data());
    Eigen::Vector3d total = gravity;
    for (int a = 0; a < count; ++a) total += fn[a] * test.contacts[a].normal;
    const Eigen::Vector3d end_velocity = test.velocity + h / m * total;
    for (int a = 0; a < count; ++a) {
      const NormalContact& contact = test.contacts[a];
      const double implied =
          k * contact.depth -
          resistance * contact.normal.dot(end_velocity - contact.surface_velocity);
      EXPECT_GE(fn[a], 0.0);
      if (fn[a] > 0.0) {
        EXPECT_NEAR(fn[a], implied, 1e-9 * std::abs(implied)) << "contact " << a;
      } else {
        EXPECT_LE(implied, 1e-12) << "contact " << a << " was left out but would push";
        ++pulling_left_out;
      }
    }
  }
  EXPECT_GE(pulling_left_out, 1);  // the active set did have to drop a contact somewhere
}

// Random sets of two to six contacts, some at sharp angles to each other (where solving, dropping
// the pulling ones and solving again can cycle): the forces always form the one consistent set.
TEST(LinearlyImplicitNormalForces, RandomContactSetsAreAlwaysConsistent) {
  std::mt19937_64 random(17);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double k = 5000.0, c = 5.0,
               m = 2e-4;  // N/m, N*s/m, kg: the contact defaults, a light particle
  int dropped = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const int count = 2 + trial % 5;
    const double h = 1e-5 * std::pow(10.0, 2.0 * (unit(random) + 1.0));  // s, 1e-5 to 1e-1
    const double resistance = c + h * k;
    const Eigen::Vector3d base =
        Eigen::Vector3d(unit(random), unit(random), unit(random)).normalized();
    std::vector<NormalContact> contacts;
    for (int a = 0; a < count; ++a) {
      // Half the normals within about 25 degrees of one another, the rest anywhere.
      const Eigen::Vector3d spread(unit(random), unit(random), unit(random));
      const Eigen::Vector3d normal = (a % 2 == 0 ? base + 0.4 * spread : spread).normalized();
      contacts.push_back({normal, 1e-3 * (unit(random) + 1.0),
                          0.5 * Eigen::Vector3d(unit(random), unit(random), unit(random))});
    }
    const Eigen::Vector3d velocity =
        2.0 * Eigen::Vector3d(unit(random), unit(random), unit(random));  // m/s
    const Eigen::Vector3d other =
        1e-2 * Eigen::Vector3d(unit(random), unit(random), unit(random));  // N
    std::vector<double> fn(contacts.size());
    linearly_implicit_normal_forces(contacts.data(), count, velocity, other, m, h, k, c, fn.data());
    Eigen::Vector3d total = other;
    for (int a = 0; a < count; ++a) total += fn[a] * contacts[a].normal;
    const Eigen::Vector3d end_velocity = velocity + h / m * total;
    // N: rounding, amplified by recomputing v' (h R / m reaches 2.5e5 here), allowed on the forces
    // in play
    double tolerance = 0.0;
    for (int a = 0; a < count; ++a)
      tolerance = std::max(tolerance, std::abs(fn[a]) + k * contacts[a].depth);
    tolerance *= 1e-11 * (1.0 + h * resistance / m);
    for (int a = 0; a < count; ++a) {
      const NormalContact& contact = contacts[a];
      const double implied =
          k * contact.depth -
          resistance * contact.normal.dot(end_velocity - contact.surface_velocity);
      ASSERT_GE(fn[a], 0.0);
      if (fn[a] > 0.0) {
        ASSERT_NEAR(fn[a], implied, tolerance) << "trial " << trial << " contact " << a;
      } else {
        ASSERT_LE(implied, tolerance)
            << "trial " << trial << " contact " << a << " left out but would push";
        ++dropped;
      }
    }
  }
  EXPECT_GT(dropped, 100);  // the sets are often partial
}

// A particle pressed by gravity into a V between two planes (each 30 degrees from level), stepped
// by symplectic Euler at h c / m = 10: solved together, the two contacts bring it to rest at its
// sag; solved one after the other (each blind to the other's force), it never settles.
double wedge_speed_after(double seconds, bool together) {
  const double k = 1000.0, c = 0.2, m = 1.5e-5, r = 0.005;  // N/m, N*s/m, kg, m (contact radius)
  const double h = 10.0 * m / c;                            // s
  const Eigen::Vector3d left(std::sin(0.5236), std::cos(0.5236), 0.0),
      right(-left.x(), left.y(), 0.0);
  const Eigen::Vector3d gravity(0.0, -m * kStandardGravity, 0.0);  // N
  Eigen::Vector3d x(0.0, 0.02, 0.0), v(0.3, 0.0, 0.0);             // m, m/s
  const int steps = static_cast<int>(std::lround(seconds / h));
  for (int s = 0; s < steps; ++s) {
    std::vector<NormalContact> touching;
    for (const Eigen::Vector3d& n : {left, right})
      if (r - n.dot(x) > 0.0) touching.push_back({n, r - n.dot(x), Eigen::Vector3d::Zero()});
    Eigen::Vector3d force = gravity;
    if (together) {
      double fn[2] = {0.0, 0.0};
      if (!touching.empty())
        linearly_implicit_normal_forces(touching.data(), static_cast<int>(touching.size()), v,
                                        gravity, m, h, k, c, fn);
      for (std::size_t a = 0; a < touching.size(); ++a) force += fn[a] * touching[a].normal;
    } else {
      for (const NormalContact& contact : touching)
        force += linearly_implicit_normal_force(contact.depth, v.dot(contact.normal),
                                                force.dot(contact.normal), m, h, k, c) *
                 contact.normal;
    }
    v += h / m * force;
    x += h * v;
  }
  return v.norm();
}

TEST(ImplicitContactParticle, RestsInAWedgeOnlyWhenItsContactsAreSolvedTogether) {
  EXPECT_LT(wedge_speed_after(2.0, true), 1e-9);   // m/s: at rest
  EXPECT_GT(wedge_speed_after(2.0, false), 1e-6);  // still moving after 2 s (measured 7 mm/s)
}

// One particle of mass m dropped onto a plane, along its normal, by symplectic Euler: y is its
// height above the contact surface (m), contact when y < 0. Returns the largest |y| seen after
// `settle` s, or infinity when the motion blows up.
double bounce(double h, bool implicit, double settle, double* final_height) {
  const double k = 1000.0, c = 0.2, m = 1.5e-5;  // the sphere drape's contact on a 129 x 129 sheet
  double y = 0.01, v = 0.0, worst_after_settle = 0.0;
  const int steps = static_cast<int>(std::lround(1.0 / h));
  for (int s = 0; s < steps; ++s) {
    const double gravity = -m * kStandardGravity;  // N
    double fn = 0.0;
    if (y < 0.0)
      fn = implicit ? linearly_implicit_normal_force(-y, v, gravity, m, h, k, c)
                    : penalty_normal_force(-y, v, k, c);
    v += h / m * (gravity + fn);
    y += h * v;
    if (!std::isfinite(y) || std::abs(y) > 1.0) return std::numeric_limits<double>::infinity();
    if (s * h > settle)
      worst_after_settle = std::max(worst_after_settle, std::abs(y + m * kStandardGravity / k));
  }
  *final_height = y;
  return worst_after_settle;
}

TEST(ImplicitContactParticle, SettlesAtTheSagAtStepsWhereTheExplicitForceDiverges) {
  const double m = 1.5e-5, c = 0.2, k = 1000.0;
  const double explicit_limit =
      (std::sqrt(c * c / (m * m) + 4.0 * k / m) - c / m) / (k / m);  // s, stability.hpp
  for (double factor : {3.0, 30.0}) {
    const double h = factor * explicit_limit;
    double height = 0.0;
    EXPECT_FALSE(std::isfinite(bounce(h, false, 0.5, &height)))
        << "explicit penalty at " << factor << " x its limit";
    const double deviation = bounce(h, true, 0.5, &height);
    ASSERT_TRUE(std::isfinite(deviation)) << factor;
    const double sag = m * kStandardGravity / k;      // m
    EXPECT_NEAR(height, -sag, 1e-3 * sag) << factor;  // rests at the penalty sag
    EXPECT_LT(deviation, 1e-3 * sag) << factor;       // and stays there
  }
}

TEST(ImplicitContactParticle, WithinTheExplicitLimitBothLandTheSame) {
  const double h = 1e-6;  // s, far inside both limits
  double explicit_height = 0.0, implicit_height = 0.0;
  ASSERT_TRUE(std::isfinite(bounce(h, false, 0.5, &explicit_height)));
  ASSERT_TRUE(std::isfinite(bounce(h, true, 0.5, &implicit_height)));
  EXPECT_NEAR(implicit_height, explicit_height, 1e-9);  // m: both at the sag, 0.15 um
}

// A 0.5 m sheet of 21 x 21 light particles (0.11 g) lying flat at y = 0.005 m, the contact
// thickness.
GridClothSpec light_sheet() { return fixtures::soft_sheet(21, 0.5, {0.0, 0.005, 0.0}, 0.05); }
constexpr ContactParameters kHeavyContact{1000.0,
                                          2.0};  // N/m, N*s/m: 2 m / c = 0.11 ms per particle

TEST(ImplicitContactStep, SymplecticEulerStepIgnoresTheContactAndVerletsKeepsIt) {
  const ClothModel model = build_grid_cloth(light_sheet());
  const ContactRates contact{kHeavyContact.stiffness, kHeavyContact.damping};
  const double springs_only = symplectic_euler_stable_step(model, 0.1);
  const double with_contact = symplectic_euler_stable_step(model, 0.1, contact);
  ASSERT_LT(with_contact, 0.5 * springs_only);  // the contact damping would bound an explicit step
  EXPECT_EQ(stable_step_estimate(model, 0.1, contact, Integrator::symplectic_euler), springs_only);
  EXPECT_EQ(stable_step_estimate(model, 0.1, contact, Integrator::verlet), with_contact);
  EXPECT_EQ(stable_step_estimate(model, 0.1, contact, Integrator::leapfrog), with_contact);
}

// A sheet of light particles laid on a floor whose contact damping bounds the explicit step far
// below the springs' bound. At the springs' step, symplectic Euler (implicit contact) settles at
// the sag with the normal forces carrying the weight; Verlet, whose contact force is explicit,
// diverges there.
struct FloorRun {
  SolverStatus status = SolverStatus::ok;
  double normal_force = 0.0;  // N, summed over the floor's contacts at the end
  double lowest_normal_force =
      std::numeric_limits<double>::infinity();  // N, over the last quarter second
  double highest_normal_force = 0.0;            // N, over the last quarter second
  double max_penetration = 0.0;                 // m, at the end
};

FloorRun rest_on_floor(Integrator integrator, double seconds) {
  const GridClothSpec spec = light_sheet();
  auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  const Collider floor = fixtures::floor_collider();  // friction 0.3
  auto contacts = std::make_shared<const ContactModel>(std::vector<Collider>{floor}, kHeavyContact,
                                                       spec.thickness);
  SpringDamperSettings settings;
  settings.air_damping = 0.1;
  settings.contacts = contacts;
  settings.integrator = integrator;
  const double h =
      0.8 * symplectic_euler_stable_step(*model, settings.air_damping);  // s, the springs' step
  SpringDamperSolver solver("floor", model, initial_grid_state(*model, spec, 0.0, 0), settings);
  const int steps = static_cast<int>(std::lround(seconds / h));
  FloorRun run;
  for (int s = 0; s < steps && solver.status() == SolverStatus::ok; ++s) {
    solver.step(h);
    if (solver.state().time < seconds - 0.25) continue;
    run.lowest_normal_force =
        std::min(run.lowest_normal_force, solver.contact_totals()[0].normal_force);
    run.highest_normal_force =
        std::max(run.highest_normal_force, solver.contact_totals()[0].normal_force);
  }
  run.status = solver.status();
  if (run.status != SolverStatus::ok) return run;
  run.normal_force = solver.contact_totals()[0].normal_force;
  run.max_penetration =
      compute_collision_metrics(*model, solver.state(), *contacts, solver.state().time)
          .max_penetration;
  return run;
}

TEST(ImplicitContactStep, ClothRestsOnAHeavilyDampedFloorAtTheSpringsStep) {
  const double particle_mass = 0.05 / (21 * 21);  // kg
  const FloorRun ours = rest_on_floor(Integrator::symplectic_euler, 1.0);
  ASSERT_EQ(ours.status, SolverStatus::ok);
  const double weight = 0.05 * kStandardGravity;  // N
  EXPECT_NEAR(ours.normal_force, weight, 0.01 * weight);
  const double sag = particle_mass * kStandardGravity / 1000.0;  // m
  EXPECT_NEAR(ours.max_penetration, sag, 0.05 * sag);

  EXPECT_NEAR(ours.lowest_normal_force, weight,
              0.01 * weight);  // at rest for the last quarter second
  EXPECT_NEAR(ours.highest_normal_force, weight, 0.01 * weight);

  // Verlet's explicit contact cannot hold the sheet at this step: the damper overshoots, the sheet
  // chatters off the floor and the normal force swings between zero and over a thousand times the
  // weight.
  const FloorRun verlet = rest_on_floor(Integrator::verlet, 1.0);
  ASSERT_EQ(verlet.status,
            SolverStatus::ok);  // the contact only pushes, so the chatter stays bounded
  EXPECT_LT(verlet.lowest_normal_force, 0.5 * weight);
  EXPECT_GT(verlet.highest_normal_force, 2.0 * weight);
}

}  // namespace
}  // namespace drapelab
