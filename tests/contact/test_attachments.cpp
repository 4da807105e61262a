// Articulated colliders (a collider's pose and motion given in its parent's frame) and pinned
// particles carried by colliders (cloth.pins[].attach), in our solver under every integrator.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <memory>
#include <vector>

#include "drapelab/attachments.hpp"
#include "drapelab/collider.hpp"
#include "drapelab/grid_cloth.hpp"
#include "drapelab/integrators.hpp"
#include "drapelab/spring_damper_solver.hpp"
#include "fixtures/sheets.hpp"

namespace drapelab {
namespace {

ColliderKeyframe key(double t, const Eigen::Vector3d& center, const Eigen::Vector3d& rotation) {
  ColliderKeyframe k;
  k.t = t;
  k.center = center;
  k.rotation = rotation;
  return k;
}

// A three-level chain: a pelvis that moves and turns by keyframes, a torso turning at a constant
// rate about its own centre in the pelvis's frame, and an arm swinging by keyframes in the
// torso's.
struct Chain {
  ColliderFrame pelvis, torso;
  Collider arm;
  Chain() {
    pelvis.rotation = {0.0, 10.0, 0.0};
    pelvis.motion.keyframes = {key(0.0, {0.0, 1.0, 0.0}, {0.0, 0.0, 0.0}),
                               key(1.0, {0.5, 1.1, -0.3}, {20.0, 70.0, -10.0}),
                               key(2.0, {0.2, 0.9, 0.1}, {0.0, 150.0, 5.0})};
    torso.center = {0.0, 0.3, 0.05};
    torso.rotation = {5.0, 0.0, 0.0};
    torso.motion.velocity = {0.02, 0.0, 0.0};
    torso.motion.angular_velocity = {0.0, 40.0, 15.0};  // deg/s
    arm.name = "arm";
    arm.shape = ColliderShape::capsule;
    arm.rotation = {0.0, 0.0, 12.0};
    arm.motion.keyframes = {key(0.0, {0.25, -0.1, 0.0}, {0.0, 0.0, 0.0}),
                            key(0.8, {0.27, -0.1, 0.02}, {-30.0, 0.0, 0.0}),
                            key(1.6, {0.25, -0.12, 0.0}, {35.0, 5.0, 0.0})};
    arm.parent = "torso";
    arm.ancestors = {torso, pelvis};  // nearest first
  }
};

TEST(ParentedColliders, WorldPoseIsTheCompositionOfTheChain) {
  const Chain chain;
  for (int step = 0; step <= 50; ++step) {
    const double t = 0.045 * step;  // s, past the last keyframes too
    const Eigen::Isometry3d expected =
        frame_pose(chain.pelvis, t) * frame_pose(chain.torso, t) * frame_pose(chain.arm.frame(), t);
    const Eigen::Isometry3d pose = collider_pose(chain.arm, t);
    EXPECT_LT((pose.matrix() - expected.matrix()).cwiseAbs().maxCoeff(), 1e-14) << "t " << t;
  }
}

TEST(ParentedColliders, PointVelocityIsTheRateOfTheComposedPose) {
  const Chain chain;
  const Eigen::Vector3d material(0.03, -0.2, 0.01);  // m, a point of the arm in its own frame
  const double delta = 1e-6;                         // s
  double worst = 0.0;
  for (double t : {0.1, 0.37, 0.55, 0.93, 1.2, 1.45}) {  // inside every keyframe segment
    const Eigen::Vector3d p = collider_pose(chain.arm, t) * material;
    const Eigen::Vector3d rate = (collider_pose(chain.arm, t + delta) * material -
                                  collider_pose(chain.arm, t - delta) * material) /
                                 (2.0 * delta);
    const Eigen::Vector3d velocity = collider_point_velocity(chain.arm, t, p);
    EXPECT_GT(velocity.norm(), 0.1);  // m/s: every level moves
    worst = std::max(worst, (velocity - rate).norm());
  }
  EXPECT_LT(worst, 1e-7);  // m/s; the central difference's error is ~1e-9 here
  RecordProperty("velocity_worst_difference", std::to_string(worst));
}

TEST(ParentedColliders, AChildMovesWhenOnlyItsParentDoes) {
  Collider still;
  still.center = {0.1, 0.0, 0.0};
  EXPECT_FALSE(still.moves());
  ColliderFrame turning;
  turning.motion.angular_velocity = {0.0, 90.0, 0.0};
  still.ancestors = {turning};
  EXPECT_TRUE(still.moves());
  const Eigen::Vector3d p = collider_pose(still, 1.0).translation();  // turned a quarter
  EXPECT_NEAR(p.x(), 0.0, 1e-15);
  EXPECT_NEAR(p.z(), -0.1, 1e-15);
}

// A 5 x 5 sheet whose two corners of one edge are pinned and carried by a capsule that moves and
// turns about two axes.
struct CarriedSheet {
  GridClothSpec spec = fixtures::soft_sheet(5, 0.2, {0.0, 1.0, 0.0}, 0.05);
  Collider bar;
  CarriedSheet() {
    spec.pins = {PinIndex{0}, PinIndex{4}};
    bar.name = "bar";
    bar.shape = ColliderShape::capsule;
    bar.center = {0.0, 1.05, -0.1};
    bar.motion.velocity = {0.2, 0.1, 0.0};             // m/s
    bar.motion.angular_velocity = {30.0, 120.0, 0.0};  // deg/s
  }
};

TEST(Attachments, CarriedParticlesKeepTheirOffsetAndTheBodysVelocityUnderEveryIntegrator) {
  const CarriedSheet sheet;
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(sheet.spec));
  const ClothState initial = initial_grid_state(*model, sheet.spec, 0.0, 0);
  const auto attachments = std::make_shared<const Attachments>(
      make_attachments({sheet.bar}, {{0, 0}, {4, 0}}, initial.x, 0.0));
  // The offsets, from the start positions: what the particles must keep in the bar's frame.
  const Eigen::Isometry3d start_pose = collider_pose(sheet.bar, 0.0);
  std::vector<Eigen::Vector3d> offset;
  for (int i : {0, 4}) offset.push_back(start_pose.inverse() * Eigen::Vector3d(initial.x.col(i)));
  for (Integrator integrator : all_integrators()) {
    SCOPED_TRACE(integrator_name(integrator));
    SpringDamperSettings settings;
    settings.integrator = integrator;
    settings.air_damping = 1.0;
    settings.attachments = attachments;
    SpringDamperSolver solver("carried", model, initial, settings);
    // s: large steps for the implicit schemes; explicit Euler, stable only while damping
    // outweighs its gain, below kd / ks of these springs
    const double h = integrator == Integrator::vbd || integrator == Integrator::implicit_euler
                         ? 1.0 / 240.0
                     : integrator == Integrator::explicit_euler ? 5e-6
                                                                : 1e-4;
    const int steps = static_cast<int>(std::lround(0.5 / h));
    double worst_position = 0.0, worst_velocity = 0.0;
    for (int k = 0; k < steps; ++k) {
      solver.step(h);
      const double t = solver.state().time;
      const Eigen::Isometry3d pose = collider_pose(sheet.bar, t);
      for (std::size_t a = 0; a < 2; ++a) {
        const int i = a == 0 ? 0 : 4;
        const Eigen::Vector3d expected = pose * offset[a];
        worst_position = std::max(worst_position, (solver.state().x.col(i) - expected).norm());
        worst_velocity = std::max(
            worst_velocity,
            (solver.state().v.col(i) - collider_point_velocity(sheet.bar, t, expected)).norm());
      }
    }
    ASSERT_EQ(solver.status(), SolverStatus::ok) << solver.message();
    EXPECT_LT(worst_position, 1e-9);  // m
    EXPECT_LT(worst_velocity, 1e-9);  // m/s
    // The cloth came along: its far edge hangs within the sheet's size of the carried corners.
    const Eigen::Vector3d carried = 0.5 * (solver.state().x.col(0) + solver.state().x.col(4));
    const Eigen::Vector3d far = 0.5 * (solver.state().x.col(20) + solver.state().x.col(24));
    EXPECT_LT((far - carried).norm(), 0.2 * 1.1);
    EXPECT_GT((carried - Eigen::Vector3d(initial.x.col(0))).norm(), 0.05);  // m: it moved
  }
}

TEST(Attachments, AStillPinStaysWhereItIsBesideACarriedOne) {
  CarriedSheet sheet;
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(sheet.spec));
  const ClothState initial = initial_grid_state(*model, sheet.spec, 0.0, 0);
  SpringDamperSettings settings;
  settings.attachments =
      std::make_shared<const Attachments>(make_attachments({sheet.bar}, {{0, 0}}, initial.x, 0.0));
  SpringDamperSolver solver("half", model, initial, settings);
  for (int k = 0; k < 500; ++k) solver.step(2e-4);
  EXPECT_EQ(solver.state().x.col(4), initial.x.col(4));  // bit for bit
  EXPECT_GT((solver.state().x.col(0) - initial.x.col(0)).norm(), 0.02);
}

TEST(Attachments, AnAttachedParticleMustBePinned) {
  const CarriedSheet sheet;
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(sheet.spec));
  const ClothState initial = initial_grid_state(*model, sheet.spec, 0.0, 0);
  SpringDamperSettings settings;
  settings.attachments = std::make_shared<const Attachments>(
      make_attachments({sheet.bar}, {{12, 0}}, initial.x, 0.0));  // the middle: free
  EXPECT_THROW(SpringDamperSolver("loose", model, initial, settings), std::invalid_argument);
  EXPECT_THROW(make_attachments({sheet.bar}, {{0, 1}}, initial.x, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace drapelab
