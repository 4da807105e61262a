// Two-way coupling with dynamic colliders (colliders[].dynamic): a ball that rests in a cloth
// pinned at its corners is held by the pins (their forces sum to the weight of ball and cloth), a
// ball and a cloth falling together trade momentum and nothing else, and a ball dropped onto a
// cloth gives it energy and takes some back. Our cloth hosted in its Bullet world, and Bullet's two
// cloths.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "drapelab/attachments.hpp"
#include "drapelab/bullet/bullet_deformable_solver.hpp"
#include "drapelab/bullet/bullet_host.hpp"
#include "drapelab/bullet/bullet_softbody_solver.hpp"
#include "drapelab/collider_pose_table.hpp"
#include "drapelab/contact_model.hpp"
#include "drapelab/grid_cloth.hpp"
#include "drapelab/spring_damper_solver.hpp"

namespace drapelab {
namespace {

const Eigen::Vector3d kGravity(0.0, -9.81, 0.0);  // m/s^2
constexpr double kContactStiffness = 5000.0;      // N/m per particle
constexpr double kContactDamping = 5.0;           // N*s/m

// A 0.5 m square sheet of 0.1 kg at y = 1 m (11 x 11, damped springs) and a 0.2 kg ball of 8 cm
// radius above it; `pinned`: the sheet's four corners are pinned.
struct BallAndSheet {
  GridClothSpec spec;
  Collider ball;
  std::shared_ptr<const ClothModel> model;
  ClothState initial;

  BallAndSheet(bool pinned, const Eigen::Vector3d& ball_center, GridPlane plane = GridPlane::xz) {
    spec.nx = spec.ny = 11;
    spec.size = {0.5, 0.5};
    spec.plane = plane;
    spec.center = {0.0, 1.0, 0.0};
    spec.mass = 0.1;
    spec.thickness = 0.005;
    spec.stretch = {500.0, 0.5};
    spec.shear = {50.0, 0.05};
    spec.bend = {0.5, 0.005};
    if (pinned) spec.pins = {PinNamed{"corners"}};
    if (plane == GridPlane::xy)  // hanging: the top corners, and the bottom ones for the ball
      spec.pins = {PinNamed{"top_corners"}, PinIndex{5}};
    model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
    initial = initial_grid_state(*model, spec, 0.0, 0);
    ball.name = "ball";
    ball.shape = ColliderShape::sphere;
    ball.radius = 0.08;
    ball.center = ball_center;
    ball.dynamic_mass = 0.2;
    ball.friction = ball.static_friction = 0.3;
  }
};

// The three solvers of a scene with dynamic colliders, as the runner builds them; `guest` is our
// cloth inside its host.
struct Solvers {
  std::unique_ptr<Solver> ours, classic, deformable;
  SpringDamperSolver* guest = nullptr;
};

// `attachments`: pins carried by the ball (null: none).
Solvers make_solvers(const BallAndSheet& scene, double air_damping,
                     std::shared_ptr<const Attachments> attachments = nullptr) {
  Solvers out;
  const std::vector<Collider> colliders = {scene.ball};
  auto poses = std::make_shared<ColliderPoseTable>(colliders.size());
  poses->set_substep(0.0, 0.0);  // the ball where the scene puts it, until the host's first step
  ColliderSubstepMotion still;
  still.start = still.end = collider_pose(scene.ball, 0.0);
  poses->set(0, still);
  SpringDamperSettings settings;
  if (attachments) {
    auto carried = std::make_shared<Attachments>(*attachments);
    carried->poses = poses;  // the ball's pose is the host's body
    settings.attachments = carried;
  }
  settings.gravity = kGravity;
  settings.air_damping = air_damping;
  settings.contacts = std::make_shared<const ContactModel>(
      colliders, ContactParameters{kContactStiffness, kContactDamping}, scene.spec.thickness,
      poses);
  auto guest = std::make_unique<SpringDamperSolver>("ours", scene.model, scene.initial, settings);
  out.guest = guest.get();
  out.ours = bullet::host_in_bullet_world(std::move(guest), poses, colliders, kGravity, 1e-3);
  bullet::BulletSoftBodyOptions classic;
  classic.dt = 1e-4;
  classic.margin = classic.voxel_size = scene.spec.thickness;
  classic.gravity = kGravity;
  classic.air_damping = air_damping;
  classic.attachments = attachments;
  if (!attachments || !attachments->any_on_dynamic())  // else it refuses (tested below)
    out.classic = bullet::make_bullet_softbody_solver("classic", scene.model, scene.initial,
                                                      colliders, classic);
  bullet::BulletDeformableOptions deformable;
  deformable.dt = 2e-4;
  deformable.margin = deformable.voxel_size = scene.spec.thickness;
  deformable.gravity = kGravity;
  deformable.air_damping = air_damping;
  deformable.attachments = attachments;
  out.deformable = bullet::make_bullet_deformable_solver("deformable", scene.model, scene.initial,
                                                         colliders, deformable);
  return out;
}

double step_of(const Solver& solver) {
  switch (solver.type()) {
    case SolverType::spring_damper:
      return 2e-4;
    case SolverType::bullet_softbody:
      return 1e-4;
    case SolverType::bullet_deformable:
    case SolverType::mujoco:  // not built here
      return 2e-4;
  }
  return 1e-4;
}

BodyState ball_of(const Solver& solver) {
  const std::vector<BodyState> bodies = solver.bodies();
  EXPECT_EQ(bodies.size(), 1u);
  return bodies.empty() ? BodyState{} : bodies.front();
}

Eigen::Vector3d cloth_momentum(const ClothModel& model, const ClothState& state) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int i = 0; i < model.particle_count(); ++i) p += model.mass[i] * state.v.col(i);
  return p;
}

// The ball comes to rest in the pinned sheet. Our cloth: the pins' forces, the reactions to the
// force on every pinned particle, add up to the weight of ball and cloth within 1 %. Bullet's
// cloths: their balls come to rest where ours does, within 2 cm.
TEST(TwoWayCoupling, PinsCarryTheWeightOfBallAndCloth) {
  const BallAndSheet scene(/*pinned=*/true, {0.0, 1.1, 0.0});   // centred: it only bobs
  Solvers solvers = make_solvers(scene, /*air_damping=*/40.0);  // 1/s: the bobbing dies out
  const double duration = 5.0;                                  // s
  double ours_height = 0.0;
  for (Solver* solver : {solvers.ours.get(), solvers.classic.get(), solvers.deformable.get()}) {
    SCOPED_TRACE(solver->name());
    const double h = step_of(*solver);
    const int steps = static_cast<int>(std::lround(duration / h));
    for (int k = 0; k < steps; ++k) solver->step(h);
    ASSERT_EQ(solver->status(), SolverStatus::ok) << solver->message();
    const BodyState ball = ball_of(*solver);
    EXPECT_LT(ball.velocity.norm(), 0.01);  // m/s: at rest
    // In the sheet, not through it: the ball's bottom is below the pins, its centre above the
    // lowest particle.
    EXPECT_LT(ball.pose.translation().y() - scene.ball.radius, 1.0);
    EXPECT_GT(ball.pose.translation().y(), solver->state().x.row(1).minCoeff());
    if (solver == solvers.ours.get()) {
      ours_height = ball.pose.translation().y();
      const ClothState& s = solver->state();
      const Eigen::Matrix3Xd& force = solvers.guest->evaluate_forces(s.x, s.v, s.time, h);
      Eigen::Vector3d pins = Eigen::Vector3d::Zero();  // N: what the pins exert
      for (int i = 0; i < scene.model->particle_count(); ++i)
        if (scene.model->is_pinned(i)) pins -= force.col(i);
      const double weight = (scene.ball.dynamic_mass + scene.model->total_mass()) * 9.81;  // N
      EXPECT_NEAR(pins.y() / weight, 1.0, 0.01) << "pins " << pins.transpose();
      EXPECT_LT(std::hypot(pins.x(), pins.z()), 0.01 * weight);
      RecordProperty("pin_force_over_weight", std::to_string(pins.y() / weight));
    } else {
      EXPECT_NEAR(ball.pose.translation().y(), ours_height, 0.02);
    }
    RecordProperty(solver->name() + "_ball_height", std::to_string(ball.pose.translation().y()));
  }
}

// A free sheet thrown down at 2 m/s onto a ball 15 cm below it, both falling: they collide in free
// fall. The total momentum of cloth and ball changes by gravity's impulse alone,
// (M_ball + M_cloth) g t: the cloth's loads go onto the ball in the same substep, equal and
// opposite.
TEST(TwoWayCoupling, MomentumOfClothAndBallChangesOnlyByGravity) {
  BallAndSheet scene(/*pinned=*/false, {0.03, 0.85 - 0.08, 0.02});
  scene.initial.v.row(1).setConstant(-2.0);  // m/s
  Solvers solvers = make_solvers(scene, /*air_damping=*/0.0);
  Solver& ours = *solvers.ours;
  const double h = step_of(ours);
  const double mass = scene.ball.dynamic_mass + scene.model->total_mass();
  const Eigen::Vector3d p0 = cloth_momentum(*scene.model, ours.state());  // the ball starts still
  bool touched = false;
  double worst = 0.0;
  for (int k = 0; k < 2500; ++k) {  // 0.5 s
    ours.step(h);
    ASSERT_EQ(ours.status(), SolverStatus::ok) << ours.message();
    const BodyState ball = ball_of(ours);
    const Eigen::Vector3d p =
        cloth_momentum(*scene.model, ours.state()) + scene.ball.dynamic_mass * ball.velocity;
    const Eigen::Vector3d expected = p0 + mass * kGravity * ours.state().time;
    worst = std::max(worst, (p - expected).norm());
    touched = touched || (ball.velocity - kGravity * ours.state().time).norm() > 0.05;
  }
  EXPECT_TRUE(touched);     // the cloth pushed the ball
  EXPECT_LT(worst, 1e-10);  // N*s, of about 1.5 N*s of gravity's impulse
  RecordProperty("momentum_worst_difference", std::to_string(worst));
}

// A ball dropped 12 cm onto the pinned sheet: it slows down as the sheet takes its energy (the
// cloth's kinetic energy rises), then the sheet throws it back up (energy flows both ways), in
// every solver.
TEST(TwoWayCoupling, DroppedBallAndClothTradeEnergy) {
  const BallAndSheet scene(/*pinned=*/true, {0.0, 1.2, 0.0});
  Solvers solvers = make_solvers(scene, /*air_damping=*/0.5);
  for (Solver* solver : {solvers.ours.get(), solvers.classic.get(), solvers.deformable.get()}) {
    SCOPED_TRACE(solver->name());
    const double h = step_of(*solver);
    double impact_speed = 0.0, slowest_after = 1e9, rebound = 0.0, cloth_energy = 0.0;
    bool hit = false;
    for (int k = 0; k < static_cast<int>(std::lround(0.6 / h)); ++k) {
      solver->step(h);
      ASSERT_EQ(solver->status(), SolverStatus::ok) << solver->message();
      const double vy = ball_of(*solver).velocity.y();  // m/s
      if (!hit) {
        impact_speed = std::max(impact_speed, -vy);
        hit = impact_speed > 0.5 && -vy < 0.9 * impact_speed;  // the cloth began to slow it
        continue;
      }
      slowest_after = std::min(slowest_after, std::abs(vy));
      rebound = std::max(rebound, vy);
      double energy = 0.0;  // J
      for (int i = 0; i < scene.model->particle_count(); ++i)
        energy += 0.5 * scene.model->mass[i] * solver->state().v.col(i).squaredNorm();
      cloth_energy = std::max(cloth_energy, energy);
    }
    ASSERT_TRUE(hit);
    const double ball_energy = 0.5 * scene.ball.dynamic_mass * impact_speed * impact_speed;  // J
    // m/s: it fell the 11.5 cm gap freely, then further as the sheet gave way under it.
    EXPECT_GT(impact_speed, 0.99 * std::sqrt(2.0 * 9.81 * 0.115));
    EXPECT_LT(slowest_after, 0.1 * impact_speed);  // the sheet stopped it ...
    EXPECT_GT(cloth_energy, 0.05 * ball_energy);   // ... moving itself ...
    EXPECT_GT(rebound, 0.2 * impact_speed);        // ... and threw it back up
    RecordProperty(solver->name() + "_rebound_over_impact", std::to_string(rebound / impact_speed));
  }
}

// A ball hanging from the middle of the bottom edge of a sheet pinned at its top corners, the
// particle there attached to the top of the ball (cloth.pins[].attach on a dynamic collider). Our
// cloth: the particles' loads carry the ball, and the top pins carry ball and cloth, (M_ball +
// M_cloth) g within 1 %. Bullet's deformable cloth (its anchor): the ball hangs at rest where ours
// does, within 2 cm. (The classic cloth cannot carry it: the loader refuses the scene for it.)
TEST(TwoWayCoupling, AnAttachedBallHangsFromTheSheet) {
  // The sheet spans y from 0.75 to 1.25 m; the ball's top touches its bottom edge.
  const BallAndSheet scene(/*pinned=*/true, {0.0, 0.75 - 0.11, 0.0}, GridPlane::xy);
  const auto attachments = std::make_shared<const Attachments>(
      make_attachments({scene.ball}, {{5, 0}}, scene.initial.x, 0.0));
  Solvers solvers = make_solvers(scene, /*air_damping=*/40.0, attachments);
  bullet::BulletSoftBodyOptions classic;
  classic.dt = 1e-4;
  classic.attachments = attachments;
  EXPECT_THROW(bullet::make_bullet_softbody_solver("classic", scene.model, scene.initial,
                                                   {scene.ball}, classic),
               std::invalid_argument);
  double ours_height = 0.0;
  for (Solver* solver : {solvers.ours.get(), solvers.deformable.get()}) {
    SCOPED_TRACE(solver->name());
    const double h = step_of(*solver);
    for (int k = 0; k < static_cast<int>(std::lround(5.0 / h)); ++k) solver->step(h);
    ASSERT_EQ(solver->status(), SolverStatus::ok) << solver->message();
    const BodyState ball = ball_of(*solver);
    EXPECT_LT(ball.velocity.norm(), 0.01);                // m/s: at rest
    EXPECT_LT(ball.pose.translation().y(), 0.64 - 0.01);  // m: it pulled the sheet down
    if (solver == solvers.ours.get()) {
      ours_height = ball.pose.translation().y();
      const ClothState& s = solver->state();
      const Eigen::Matrix3Xd& force = solvers.guest->evaluate_forces(s.x, s.v, s.time, h);
      Eigen::Vector3d pins = Eigen::Vector3d::Zero();  // N: what the top pins exert
      for (int i = 0; i < scene.model->particle_count(); ++i)
        if (scene.model->is_pinned(i) && i != 5) pins -= force.col(i);
      const double weight = (scene.ball.dynamic_mass + scene.model->total_mass()) * 9.81;  // N
      EXPECT_NEAR(pins.y() / weight, 1.0, 0.01) << "pins " << pins.transpose();
      RecordProperty("hanging_pin_force_over_weight", std::to_string(pins.y() / weight));
    } else {
      EXPECT_NEAR(ball.pose.translation().y(), ours_height, 0.02);
    }
    RecordProperty(solver->name() + "_hanging_ball_height",
                   std::to_string(ball.pose.translation().y()));
  }
}

}  // namespace
}  // namespace drapelab
