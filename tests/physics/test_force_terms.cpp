// The force evaluation as terms in a named order (integrators/force_evaluator.hpp): which terms a
// world gives, the order they run in, and that each term adds exactly its own force.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "drapelab/air.hpp"
#include "drapelab/grid_cloth.hpp"
#include "drapelab/spring_damper_solver.hpp"
#include "drapelab/stability.hpp"
#include "fixtures/sheets.hpp"

namespace drapelab {
namespace {

// A 6 x 6 sheet of 0.2 kg hanging from two corners, slightly disturbed and moving.
std::shared_ptr<const ClothModel> sheet() {
  return std::make_shared<const ClothModel>(
      build_grid_cloth(fixtures::hanging_sheet(6, 0.2, fixtures::kTenfoldSprings)));
}

ClothState moving_state(const ClothModel& model) {
  ClothState state;
  state.x = model.rest_positions;
  state.v = Eigen::Matrix3Xd::Zero(3, model.particle_count());
  for (int i = 0; i < model.particle_count(); ++i) {
    state.x(2, i) += 0.01 * std::sin(1.7 * i);
    state.v.col(i) = Eigen::Vector3d(0.3 * std::cos(i), -0.2, 0.5 * std::sin(0.3 * i));
  }
  return state;
}

// A box below the sheet's centre, with sharp edges for the edge contacts.
std::shared_ptr<const ContactModel> box_under(const ClothModel& model) {
  Collider box;
  box.shape = ColliderShape::box;
  box.center = model.rest_positions.rowwise().mean() - Eigen::Vector3d(0.0, 0.3, 0.0);
  box.half_extents = {0.1, 0.1, 0.1};
  return std::make_shared<const ContactModel>(std::vector<Collider>{box},
                                              ContactParameters{1000.0, 1.0}, model.thickness);
}

std::shared_ptr<const DistanceConstraints> soft_pull(const ClothModel& model) {
  auto constraints = std::make_shared<DistanceConstraints>();
  DistanceConstraint c;
  c.a = model.particle_count() / 2;
  c.b.kind = ConstraintEnd::Kind::point;
  c.b.point = model.rest_positions.col(c.a) + Eigen::Vector3d(0.0, -0.2, 0.0);
  c.length = 0.1;
  c.mode = ConstraintMode::soft;
  c.stiffness = 50.0;
  c.damping = 0.5;
  constraints->list.push_back(c);
  return constraints;
}

AirSettings breeze() {
  AirSettings air;
  air.enabled = true;
  air.wind = {2.0, 0.0, 1.0};
  air.lift = 0.3;
  return air;
}

TEST(ForceTerms, AWorldWithEveryForceRunsEveryTermInTheNamedOrder) {
  const auto model = sheet();
  SpringDamperSettings settings;
  settings.self_collision.enabled = true;
  settings.contacts = box_under(*model);
  settings.collider_edges = true;
  settings.constraints = soft_pull(*model);
  settings.air = breeze();
  const SpringDamperSolver solver("all", model, moving_state(*model), settings);
  EXPECT_EQ(solver.force_terms(),
            (std::vector<std::string>{"body_and_springs", "self_contacts", "collider_edges",
                                      "soft_constraints", "air", "collider_contacts"}));
}

TEST(ForceTerms, ABareWorldRunsTheSpringsAlone) {
  const auto model = sheet();
  const SpringDamperSolver solver("bare", model, moving_state(*model), SpringDamperSettings{});
  EXPECT_EQ(solver.force_terms(), std::vector<std::string>{"body_and_springs"});
  // Edge contacts need a collider with sharp features: a sphere gives none.
  SpringDamperSettings round;
  Collider ball;
  ball.radius = 0.2;
  round.contacts = std::make_shared<const ContactModel>(
      std::vector<Collider>{ball}, ContactParameters{1000.0, 1.0}, model->thickness);
  round.collider_edges = true;
  const SpringDamperSolver on_ball("ball", model, moving_state(*model), round);
  EXPECT_EQ(on_ball.force_terms(),
            (std::vector<std::string>{"body_and_springs", "collider_contacts"}));
}

// Each term between particles adds its own force and nothing else: the evaluation with it less
// the one without is the term's force on its own.
TEST(ForceTerms, TheAirTermAddsExactlyTheAirForce) {
  const auto model = sheet();
  const ClothState state = moving_state(*model);
  SpringDamperSettings with_air;
  with_air.air = breeze();
  SpringDamperSolver a("air", model, state, with_air);
  SpringDamperSolver b("still", model, state, SpringDamperSettings{});
  const double t = 0.25, h = 1e-3;  // s
  const Eigen::Matrix3Xd difference =
      a.evaluate_forces(state.x, state.v, t, h) - b.evaluate_forces(state.x, state.v, t, h);
  Eigen::Matrix3Xd air = Eigen::Matrix3Xd::Zero(3, model->particle_count());
  add_air_forces(*model, with_air.air, Wind(with_air.air), t, state.x, state.v, air);
  ASSERT_GT(air.cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_LT((difference - air).cwiseAbs().maxCoeff(), 1e-12 * air.cwiseAbs().maxCoeff() + 1e-15);
}

TEST(ForceTerms, TheSoftConstraintTermAddsItsSpringAndDamper) {
  const auto model = sheet();
  const ClothState state = moving_state(*model);
  SpringDamperSettings pulled;
  pulled.constraints = soft_pull(*model);
  SpringDamperSolver a("pulled", model, state, pulled);
  SpringDamperSolver b("free", model, state, SpringDamperSettings{});
  Eigen::Matrix3Xd difference = a.evaluate_forces(state.x, state.v, 0.0, 1e-3) -
                                b.evaluate_forces(state.x, state.v, 0.0, 1e-3);
  // f = -[k (l - L) + c (v . n)] n, n from the point to the particle.
  const DistanceConstraint& c = pulled.constraints->list.front();
  const Eigen::Vector3d d = state.x.col(c.a) - c.b.point;
  const Eigen::Vector3d n = d.normalized();
  const Eigen::Vector3d expected =
      -(c.stiffness * (d.norm() - c.length) + c.damping * state.v.col(c.a).dot(n)) * n;
  EXPECT_LT((difference.col(c.a) - expected).norm(), 1e-12 * expected.norm());
  difference.col(c.a).setZero();
  EXPECT_LT(difference.cwiseAbs().maxCoeff(), 1e-15);
}

// Every term is timed under its own phase: the self-contacts' phase only counts with
// self-collision on, and a run with it spends time there.
TEST(ForceTerms, EachTermIsTimedUnderItsPhase) {
  const auto model = sheet();
  SpringDamperSettings settings;
  settings.self_collision.enabled = true;
  SpringDamperSolver solver("self", model, moving_state(*model), settings);
  for (int k = 0; k < 20; ++k) solver.step(1e-4);
  ASSERT_EQ(solver.status(), SolverStatus::ok) << solver.message();
  bool timed = false;
  for (const auto& [phase, seconds] : solver.phase_seconds())
    if (phase == "self_contacts") timed = seconds > 0.0;
  EXPECT_TRUE(timed);
}

// The step the engine gives when a scene names none: each scheme's own default, or a share of its
// stable step estimate.
TEST(DefaultStep, EachIntegratorAsksForItsOwnStep) {
  const auto model = sheet();
  const ContactRates contact{1000.0, 1.0};
  const double air = 0.1;  // 1/s
  EXPECT_EQ(default_step(*model, Integrator::implicit_euler, false, air, contact).step,
            kImplicitEulerDefaultStep);
  EXPECT_EQ(default_step(*model, Integrator::vbd, false, air, contact).step, kVbdDefaultStep);
  EXPECT_EQ(default_step(*model, Integrator::symplectic_euler, true, air, contact).step,
            kAdaptiveOuterStep);
  for (Integrator integrator : {Integrator::symplectic_euler, Integrator::rk4, Integrator::verlet,
                                Integrator::leapfrog, Integrator::explicit_euler}) {
    const DefaultStep chosen = default_step(*model, integrator, false, air, contact);
    EXPECT_TRUE(chosen.from_stable_step);
    EXPECT_EQ(chosen.factor, 0.9);
    EXPECT_EQ(chosen.step, 0.9 * stable_step_estimate(*model, air, contact, integrator));
  }
  // Explicit Euler on undamped springs has no stable step: a tenth of symplectic Euler's.
  const auto undamped = std::make_shared<const ClothModel>(
      build_grid_cloth(fixtures::hanging_sheet(6, 0.2, fixtures::kUndampedSprings)));
  const DefaultStep fallback = default_step(*undamped, Integrator::explicit_euler, false, 0.0, {});
  EXPECT_EQ(fallback.factor, 0.1);
  EXPECT_EQ(fallback.bound_integrator, Integrator::symplectic_euler);
  EXPECT_EQ(fallback.step, 0.1 * symplectic_euler_stable_step(*undamped, 0.0, {}));
  EXPECT_GT(fallback.step, 0.0);
}

}  // namespace
}  // namespace drapelab
