// Soft constraints ending on a dynamic collider (a string to a rigid body): a ball hanging from a
// pinned particle on a damped spring settles at Hooke's extension M g / k and swings with the
// damped spring's period, in our cloth under every integrator and in Bullet's two cloths; a sheet
// and a ball tied together by four strings fall with the momentum of gravity's impulse alone.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "drapelab/bullet/bullet_deformable_solver.hpp"
#include "drapelab/bullet/bullet_host.hpp"
#include "drapelab/bullet/bullet_softbody_solver.hpp"
#include "drapelab/collider_pose_table.hpp"
#include "drapelab/distance_constraints.hpp"
#include "drapelab/grid_cloth.hpp"
#include "drapelab/integrators.hpp"
#include "drapelab/spring_damper_solver.hpp"

namespace drapelab {
namespace {

const Eigen::Vector3d kGravityVector(0.0, -9.81, 0.0);  // m/s^2
constexpr double kBallMass = 0.2;                       // kg
constexpr double kBallRadius = 0.05;                    // m

Collider ball_at(const Eigen::Vector3d& center) {
  Collider ball;
  ball.name = "ball";
  ball.shape = ColliderShape::sphere;
  ball.radius = kBallRadius;
  ball.center = center;
  ball.dynamic_mass = kBallMass;
  return ball;
}

// Soft strings from particles to the top of the ball.
std::shared_ptr<const DistanceConstraints> strings_to_ball(const Collider& ball,
                                                           const std::vector<int>& particles,
                                                           double length, double stiffness,
                                                           double damping) {
  auto constraints = std::make_shared<DistanceConstraints>();
  constraints->colliders = {ball};
  for (int particle : particles) {
    DistanceConstraint c;
    c.a = particle;
    c.b.kind = ConstraintEnd::Kind::collider_point;
    c.b.collider = 0;
    c.b.point = Eigen::Vector3d(0.0, kBallRadius, 0.0);  // in the ball's frame
    c.length = length;
    c.mode = ConstraintMode::soft;
    c.stiffness = stiffness;
    c.damping = damping;
    constraints->list.push_back(c);
  }
  return constraints;
}

// Our cloth hosted in a Bullet world with the ball, as the runner builds it.
std::unique_ptr<Solver> hosted_ours(std::shared_ptr<const ClothModel> model,
                                    const ClothState& initial, const Collider& ball,
                                    std::shared_ptr<const DistanceConstraints> constraints,
                                    Integrator integrator) {
  auto poses = std::make_shared<ColliderPoseTable>(1);
  poses->set_substep(0.0, 0.0);
  ColliderSubstepMotion still;
  still.start = still.end = collider_pose(ball, 0.0);
  poses->set(0, still);
  SpringDamperSettings settings;
  settings.integrator = integrator;
  settings.gravity = kGravityVector;
  settings.constraints = constraints_on_own_bodies(std::move(constraints), poses);
  auto guest = std::make_unique<SpringDamperSolver>("ours", std::move(model), initial, settings);
  return bullet::host_in_bullet_world(std::move(guest), poses, {ball}, kGravityVector, 1e-3);
}

std::unique_ptr<Solver> classic_cloth(std::shared_ptr<const ClothModel> model,
                                      const ClothState& initial, const Collider& ball,
                                      std::shared_ptr<const DistanceConstraints> constraints) {
  bullet::BulletSoftBodyOptions options;
  options.dt = 1e-4;
  options.gravity = kGravityVector;
  options.constraints = std::move(constraints);
  return bullet::make_bullet_softbody_solver("classic", std::move(model), initial, {ball}, options);
}

std::unique_ptr<Solver> deformable_cloth(std::shared_ptr<const ClothModel> model,
                                         const ClothState& initial, const Collider& ball,
                                         std::shared_ptr<const DistanceConstraints> constraints) {
  bullet::BulletDeformableOptions options;
  options.dt = 1e-4;
  options.gravity = kGravityVector;
  options.constraints = std::move(constraints);
  return bullet::make_bullet_deformable_solver("deformable", std::move(model), initial, {ball},
                                               options);
}

std::string scientific(double value) {
  std::ostringstream text;
  text.precision(6);
  text << std::scientific << value;
  return text.str();
}

BodyState hanging_ball(const Solver& solver) {
  const std::vector<BodyState> bodies = solver.bodies();
  EXPECT_EQ(bodies.size(), 1u);
  return bodies.empty() ? BodyState{} : bodies.front();
}

// A 0.2 m square of four particles, level at y = 1 m, all pinned: a fixed frame to hang from.
struct PinnedFrame {
  GridClothSpec spec;
  std::shared_ptr<const ClothModel> model;
  ClothState initial;

  PinnedFrame() {
    spec.nx = spec.ny = 2;
    spec.size = {0.2, 0.2};
    spec.plane = GridPlane::xz;
    spec.center = {0.0, 1.0, 0.0};
    spec.mass = 0.01;
    spec.stretch = {100.0, 0.0};
    spec.pins = {PinNamed{"corners"}};
    model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
    initial = initial_grid_state(*model, spec, 0.0, 0);
  }
};

struct Swing {
  double rest_height = 0.0;      // m: the ball's centre after 4 s
  double first_turn_time = 0.0;  // s: when it first stops falling
};

Swing hang(Solver& solver, double h) {
  Swing swing;
  for (int k = 0; k < static_cast<int>(std::lround(4.0 / h)); ++k) {
    solver.step(h);
    EXPECT_EQ(solver.status(), SolverStatus::ok) << solver.message();
    if (solver.status() != SolverStatus::ok) return swing;
    if (swing.first_turn_time == 0.0 && hanging_ball(solver).velocity.y() > 0.0)
      swing.first_turn_time = solver.state().time;
  }
  swing.rest_height = hanging_ball(solver).pose.translation().y();
  return swing;
}

// The ball starts with the string at its length L and hangs at rest at y_a - L - M g / k - r.
// Its first turn comes after half the damped period, pi / (w sqrt(1 - zeta^2)).
TEST(BodyStrings, ABallHangsAtHookesExtension) {
  const PinnedFrame frame;
  const int corner = 0;
  const Eigen::Vector3d a = frame.initial.x.col(corner);
  const double length = 0.3, stiffness = 40.0, damping = 2.0;  // m, N/m, N*s/m
  const Collider ball = ball_at(a - Eigen::Vector3d(0.0, length + kBallRadius, 0.0));
  const auto strings = strings_to_ball(ball, {corner}, length, stiffness, damping);
  const double expected = a.y() - length - kBallMass * 9.81 / stiffness - kBallRadius;  // m
  const double w = std::sqrt(stiffness / kBallMass);                                    // rad/s
  const double zeta = damping / (2.0 * std::sqrt(stiffness * kBallMass));
  const double half_period = M_PI / (w * std::sqrt(1.0 - zeta * zeta));  // s
  std::vector<std::unique_ptr<Solver>> solvers;
  for (Integrator integrator : all_integrators())
    solvers.push_back(hosted_ours(frame.model, frame.initial, ball, strings, integrator));
  solvers.push_back(classic_cloth(frame.model, frame.initial, ball, strings));
  solvers.push_back(deformable_cloth(frame.model, frame.initial, ball, strings));
  for (std::size_t s = 0; s < solvers.size(); ++s) {
    const std::string label = s < all_integrators().size()
                                  ? std::string("ours ") + integrator_name(all_integrators()[s])
                                  : solvers[s]->name();
    SCOPED_TRACE(label);
    const Swing swing = hang(*solvers[s], 1e-4);
    EXPECT_NEAR(swing.rest_height, expected, 1e-5);  // m, of a 49 mm extension
    EXPECT_NEAR(swing.first_turn_time / half_period, 1.0, 0.01);
    RecordProperty(label + "_rest_height_error", scientific(swing.rest_height - expected));
    RecordProperty(label + "_half_period_ratio", scientific(swing.first_turn_time / half_period));
  }
}

// A free 0.4 m sheet (9 x 9, 40 g) and the ball hanging 0.3 m below it on four strings from its
// corners, let go at rest: the strings exchange equal and opposite impulses, so the momentum of
// sheet and ball is gravity's impulse (M + m) g t. Exactly (to rounding) for the schemes whose
// body load is the force their particles moved with (one evaluation: the Euler pair; midpoint's
// last evaluation is its only one that moves the particles); within 1 % for the others, whose
// bodies take the force of the step's last evaluation.
TEST(BodyStrings, SheetAndBallTiedByStringsKeepTheirMomentum) {
  GridClothSpec spec;
  spec.nx = spec.ny = 9;
  spec.size = {0.4, 0.4};
  spec.plane = GridPlane::xz;
  spec.center = {0.0, 1.0, 0.0};
  spec.mass = 0.04;
  spec.stretch = {400.0, 0.04};
  spec.shear = {40.0, 0.004};
  spec.bend = {0.4, 0.0004};
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  ClothState initial = initial_grid_state(*model, spec, 0.0, 0);
  const Collider ball = ball_at({0.0, 1.0 - 0.3 - kBallRadius, 0.0});
  const std::vector<int> corners = {0, 8, 72, 80};
  const double length =
      (initial.x.col(0) - (ball.center + Eigen::Vector3d(0, kBallRadius, 0))).norm();
  // The ball starts falling faster than the sheet, so the strings pull from the start.
  initial.v.setZero();
  const auto strings = strings_to_ball(ball, corners, 0.95 * length, 50.0, 0.05);
  const double mass = kBallMass + model->total_mass();  // kg
  for (Integrator integrator : all_integrators()) {
    SCOPED_TRACE(integrator_name(integrator));
    auto ours = hosted_ours(model, initial, ball, strings, integrator);
    const double h = 1e-4;
    double worst = 0.0;               // N*s
    for (int k = 0; k < 5000; ++k) {  // 0.5 s
      ours->step(h);
      ASSERT_EQ(ours->status(), SolverStatus::ok) << ours->message();
      Eigen::Vector3d p = kBallMass * hanging_ball(*ours).velocity;
      for (int i = 0; i < model->particle_count(); ++i)
        p += model->mass[i] * ours->state().v.col(i);
      worst = std::max(worst, (p - mass * kGravityVector * ours->state().time).norm());
    }
    const double impulse = mass * 9.81 * 0.5;  // N*s
    const bool exact = integrator == Integrator::symplectic_euler ||
                       integrator == Integrator::explicit_euler ||
                       integrator == Integrator::midpoint;
    EXPECT_LT(worst / impulse, exact ? 1e-10 : 1e-2);
    RecordProperty(std::string(integrator_name(integrator)) + "_momentum_error_over_impulse",
                   scientific(worst / impulse));
  }
}

}  // namespace
}  // namespace drapelab
